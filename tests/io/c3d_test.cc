#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/atomic_file.h"
#include "io/c3d_reader.h"
#include "io/c3d_writer.h"
#include "tests/test_support.h"

namespace mocapsolve {
namespace {

// ---------------------------------------------------------------------------------------
// Helpers.

// Markers at distinct smooth paths, a few gaps, residuals and camera masks.
MarkerTrajectories Synthetic(int num_markers, int num_frames, unsigned seed = 1) {
  std::vector<std::string> labels;
  for (int m = 0; m < num_markers; ++m) labels.push_back("Subj:M" + std::to_string(m));
  MarkerTrajectories t(labels, num_frames);
  t.frame_rate = 240.0;
  t.unit = Millimetres();
  t.first_frame = 17;
  t.subject_prefixes = {"Subj:"};
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  for (int f = 0; f < num_frames; ++f) {
    for (int m = 0; m < num_markers; ++m) {
      if ((f * 7 + m * 3) % 11 == 0) continue;  // A gap.
      const Eigen::Vector3d p(1500.0 * uniform(rng), 1500.0 * uniform(rng) + 0.123456,
                              900.0 + 800.0 * uniform(rng));
      t.SetSample(f, m, p, static_cast<float>(2.0 + uniform(rng)),
                  static_cast<std::uint8_t>((f + m) % 128));
    }
  }
  return t;
}

std::string Encode(const MarkerTrajectories& t) {
  std::string bytes;
  const Status status = EncodeC3d(t, "synthetic.c3d", &bytes);
  EXPECT_TRUE(status.ok()) << status.message();
  return bytes;
}

// File offset of the values of parameter `name` in an Intel C3D image (walks the
// records the way the reader does; the test files are our own, so no bounds games).
// `skip` skips that many earlier parameters of the same name (POINT:USED, ANALOG:USED).
size_t ParameterValueOffset(const std::string& bytes, const std::string& name, int skip = 0) {
  size_t p = (static_cast<std::uint8_t>(bytes[0]) - 1) * 512 + 4;
  while (true) {
    const int length = std::abs(static_cast<int>(static_cast<std::int8_t>(bytes[p])));
    const int group = static_cast<std::int8_t>(bytes[p + 1]);
    if (length == 0) return std::string::npos;
    const size_t link = p + 2 + length;
    std::int16_t next;
    std::memcpy(&next, bytes.data() + link, 2);
    if (group > 0 && bytes.compare(p + 2, length, name) == 0 && skip-- == 0) {
      const int dims = static_cast<std::uint8_t>(bytes[link + 3]);
      return link + 4 + dims;
    }
    if (next == 0) return std::string::npos;
    p = link + next;
  }
}

void PutU16(std::string* bytes, size_t offset, std::uint16_t value) {
  std::memcpy(&(*bytes)[offset], &value, 2);  // Little-endian host, Intel file.
}

Status Parse(const std::string& bytes, MarkerTrajectories* t, C3dFileInfo* info = nullptr) {
  return ParseC3d(bytes, "bad.c3d", t, info);
}

// A bad-input error: one line, naming the file.
void ExpectOneLineError(const Status& status, const std::string& file, const std::string& part) {
  ASSERT_FALSE(status.ok());
  EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
  EXPECT_EQ(status.message().rfind(file + ":", 0), 0u) << status.message();
  EXPECT_NE(status.message().find(part), std::string::npos)
      << "expected '" << part << "' in: " << status.message();
}

// ---------------------------------------------------------------------------------------
// (a) c3d.org sample01 in six encodings.

TEST(C3dReader, SixEncodingsOfEb015DecodeToTheSameTrial) {
  const char* kNames[] = {"pi", "pr", "si", "sr", "vi", "vr"};
  const C3dProcessor kProcessors[] = {C3dProcessor::kIntel, C3dProcessor::kIntel,
                                      C3dProcessor::kSgiMips, C3dProcessor::kSgiMips,
                                      C3dProcessor::kDec, C3dProcessor::kDec};
  std::vector<MarkerTrajectories> trials(6);
  std::vector<C3dFileInfo> infos(6);
  for (int i = 0; i < 6; ++i) {
    MOCAPSOLVE_DATA_FILE(path, std::string("c3d/c3d.org_sample01/Eb015") + kNames[i] + ".c3d");
    const Status status = ReadC3d(path, &trials[i], &infos[i]);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(infos[i].processor, kProcessors[i]) << kNames[i];
    EXPECT_EQ(infos[i].float_storage, kNames[i][1] == 'r') << kNames[i];
    EXPECT_EQ(infos[i].analog_values_per_frame, 64) << kNames[i];  // 16 channels x 4.
  }
  const MarkerTrajectories& reference = trials[0];  // PC int.
  EXPECT_EQ(reference.num_markers(), 26);
  EXPECT_EQ(reference.num_frames(), 450);
  EXPECT_EQ(reference.frame_rate, 50.0);
  EXPECT_EQ(reference.unit.name, "mm");
  EXPECT_EQ(reference.CountMissing(), 226);
  const int pv2 = reference.FindMarker("PV2");
  ASSERT_GE(pv2, 0);
  // The interior gap; the README counts frames from 0 (indices 343-354 = C3D frame
  // numbers 344-355).
  for (int f = 343; f <= 354; ++f) EXPECT_FALSE(reference.valid(f, pv2)) << f;
  EXPECT_TRUE(reference.valid(342, pv2));
  EXPECT_TRUE(reference.valid(355, pv2));

  // int16 samples are multiples of the scale; a float file may differ from them by at
  // most half a quantization step (plus float rounding).
  const double half_step = 0.5 * std::abs(infos[0].point_scale) + 1e-4;
  for (int i = 1; i < 6; ++i) {
    const MarkerTrajectories& t = trials[i];
    ASSERT_EQ(t.labels(), reference.labels()) << kNames[i];
    ASSERT_EQ(t.num_frames(), reference.num_frames()) << kNames[i];
    EXPECT_EQ(t.frame_rate, reference.frame_rate) << kNames[i];
    EXPECT_EQ(t.first_frame, reference.first_frame) << kNames[i];
    EXPECT_EQ(t.valid_mask(), reference.valid_mask()) << kNames[i];
    const bool same_storage = infos[i].float_storage == infos[0].float_storage;
    double max_difference = 0.0;
    for (int f = 0; f < t.num_frames(); ++f) {
      for (int m = 0; m < t.num_markers(); ++m) {
        if (!t.valid(f, m)) continue;
        max_difference =
            std::max(max_difference, (t.position(f, m) - reference.position(f, m)).cwiseAbs().maxCoeff());
        EXPECT_EQ(t.camera_mask(f, m), reference.camera_mask(f, m));
      }
    }
    // Same storage: bit-identical values whatever the byte order or float format.
    EXPECT_LE(max_difference, same_storage ? 0.0 : half_step) << kNames[i];
    std::printf("Eb015%s: max |difference| to Eb015pi %.3g mm\n", kNames[i], max_difference);
  }
}

// ---------------------------------------------------------------------------------------
// (b) Every C3D of the data set, with the README's counts.

struct C3dFacts {
  const char* file;
  int markers;
  int frames;
  double rate;
  int first_frame;
  int missing;
  C3dProcessor processor;
  bool float_storage;
  int analog_values_per_frame;
};

class C3dDataSet : public ::testing::TestWithParam<C3dFacts> {};

TEST_P(C3dDataSet, LoadsWithTheDocumentedCounts) {
  const C3dFacts& facts = GetParam();
  MOCAPSOLVE_DATA_FILE(path, std::string("c3d/") + facts.file);
  MarkerTrajectories t;
  C3dFileInfo info;
  const Status status = ReadC3d(path, &t, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(t.num_markers(), facts.markers);
  EXPECT_EQ(t.num_frames(), facts.frames);
  EXPECT_EQ(t.frame_rate, facts.rate);
  EXPECT_EQ(t.first_frame, facts.first_frame);
  EXPECT_EQ(t.CountMissing(), facts.missing);
  EXPECT_EQ(t.unit.name, "mm");
  EXPECT_EQ(info.processor, facts.processor);
  EXPECT_EQ(info.float_storage, facts.float_storage);
  EXPECT_EQ(info.analog_values_per_frame, facts.analog_values_per_frame);
  // Missing samples are NaN and only NaN; valid ones are finite.
  for (Eigen::Index i = 0; i < t.positions().cols(); ++i) {
    ASSERT_EQ(t.valid_mask()[i] != 0, t.positions().col(i).allFinite()) << "sample " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(
    AllFiles, C3dDataSet,
    ::testing::Values(
        C3dFacts{"02_01.c3d", 41, 343, 120.0, 50, 0, C3dProcessor::kIntel, true, 0},
        C3dFacts{"cmu_02_05.c3d", 41, 1854, 120.0, 1, 3, C3dProcessor::kIntel, true, 0},
        C3dFacts{"cmu_dribble_shoot_basketball.c3d", 41, 494, 120.0, 187, 0, C3dProcessor::kDec,
                 false, 0},
        C3dFacts{"nick_freeform_001.c3d", 53, 1101, 120.0, 1, 3874, C3dProcessor::kIntel, true, 0},
        C3dFacts{"squat.c3d", 53, 2539, 120.0, 1, 2322, C3dProcessor::kIntel, true, 0},
        C3dFacts{"JA1Gait35.c3d", 53, 324, 250.0, 833, 1, C3dProcessor::kIntel, true, 360},
        C3dFacts{"manufacture_test_codamotion.c3d", 24, 512, 200.0, 1, 85, C3dProcessor::kIntel,
                 true, 32},
        C3dFacts{"c3d.org_sample01/Eb015pi.c3d", 26, 450, 50.0, 1, 226, C3dProcessor::kIntel,
                 false, 64}),
    [](const ::testing::TestParamInfo<C3dFacts>& info) {
      std::string name = info.param.file;
      for (char& c : name) {
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
      }
      return name;
    });

TEST(C3dReader, SubjectPrefixesAndNamedGaps) {
  MOCAPSOLVE_DATA_FILE(walk, "c3d/02_01.c3d");
  MarkerTrajectories t;
  ASSERT_TRUE(ReadC3d(walk, &t).ok());
  ASSERT_EQ(t.subject_prefixes, std::vector<std::string>{"TakeoMonday:"});
  EXPECT_EQ(t.label(0), "TakeoMonday:LBWT");  // Raw labels are kept...
  EXPECT_EQ(t.FindMarker("LBWT"), 0);         // ...and found without the prefix.
  EXPECT_EQ(t.FindMarker("TakeoMonday:LBWT"), 0);
  EXPECT_EQ(t.FindMarker("XXXX"), -1);

  MOCAPSOLVE_DATA_FILE(freeform, "c3d/nick_freeform_001.c3d");
  ASSERT_TRUE(ReadC3d(freeform, &t).ok());
  const int clav = t.FindMarker("CLAV");
  ASSERT_GE(clav, 0);
  EXPECT_EQ(t.CountMissing(clav), t.num_frames());  // CLAV missing for the whole take.
  const int strn = t.FindMarker("STRN");
  ASSERT_GE(strn, 0);
  for (int f = 620; f <= 632; ++f) EXPECT_FALSE(t.valid(f, strn)) << f;  // 0-based, as the README.
  EXPECT_TRUE(t.valid(619, strn));
  EXPECT_TRUE(t.valid(633, strn));

  MOCAPSOLVE_DATA_FILE(punch, "c3d/cmu_02_05.c3d");
  ASSERT_TRUE(ReadC3d(punch, &t).ok());
  const int rshn = t.FindMarker("RSHN");
  ASSERT_GE(rshn, 0);
  EXPECT_EQ(t.CountMissing(rshn), 3);
  EXPECT_FALSE(t.valid(0, rshn) || t.valid(1, rshn) || t.valid(2, rshn));  // At the start.
  EXPECT_EQ(t.CountMissing(), 3);

  MOCAPSOLVE_DATA_FILE(basketball, "c3d/cmu_dribble_shoot_basketball.c3d");
  ASSERT_TRUE(ReadC3d(basketball, &t).ok());
  EXPECT_EQ(t.subject_prefixes, std::vector<std::string>{"Justin:"});
  EXPECT_GE(t.FindMarker("LFHD"), 0);
}

TEST(C3dReader, JA1Gait35ZeroSampleCarriesResidual65535) {
  // The one all-zero sample of this file is marked invalid by its residual word
  // (65535.0 as float = int16 -1), so it is missing even without the all-zero rule.
  MOCAPSOLVE_DATA_FILE(path, "c3d/JA1Gait35.c3d");
  MarkerTrajectories t;
  C3dFileInfo info;
  C3dReadOptions keep_zeros;
  keep_zeros.zero_position_is_missing = false;
  ASSERT_TRUE(ReadC3d(path, &t, &info, keep_zeros).ok());
  EXPECT_EQ(t.CountMissing(), 1);
  EXPECT_EQ(info.negative_residual_samples, 1);
  EXPECT_EQ(info.analog_channels, 60);
  EXPECT_EQ(t.CountMissing(t.FindMarker("RTOE")), 1);
  EXPECT_EQ(t.label(52), "*53");  // Unlabelled points keep Vicon's names.
}

// ---------------------------------------------------------------------------------------
// (c) Write -> read round trips.

void ExpectSameTrajectories(const MarkerTrajectories& a, const MarkerTrajectories& b,
                            double residual_tolerance) {
  ASSERT_EQ(a.labels(), b.labels());
  ASSERT_EQ(a.num_frames(), b.num_frames());
  EXPECT_EQ(a.frame_rate, b.frame_rate);
  EXPECT_EQ(a.first_frame, b.first_frame);
  EXPECT_EQ(a.unit.name, b.unit.name);
  EXPECT_EQ(a.unit.metres_per_unit, b.unit.metres_per_unit);
  EXPECT_EQ(a.subject_prefixes, b.subject_prefixes);
  EXPECT_EQ(a.valid_mask(), b.valid_mask());
  for (int f = 0; f < a.num_frames(); ++f) {
    for (int m = 0; m < a.num_markers(); ++m) {
      if (!a.valid(f, m)) continue;
      // Float storage: relative precision 2^-24.
      const Eigen::Vector3d expected = a.position(f, m);
      const double tolerance = 6e-8 * expected.cwiseAbs().maxCoeff();
      ASSERT_LE((b.position(f, m) - expected).cwiseAbs().maxCoeff(), tolerance)
          << "frame " << f << " marker " << m;
      ASSERT_NEAR(b.residual(f, m), a.residual(f, m), residual_tolerance);
      ASSERT_EQ(b.camera_mask(f, m), a.camera_mask(f, m));
    }
  }
}

TEST(C3dWriter, SyntheticRoundTripKeepsValuesMasksAndMetadata) {
  const MarkerTrajectories written = Synthetic(12, 40);
  ASSERT_GT(written.CountMissing(), 0);
  MarkerTrajectories read;
  C3dFileInfo info;
  const Status status = ParseC3d(Encode(written), "synthetic.c3d", &read, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(info.processor, C3dProcessor::kIntel);
  EXPECT_TRUE(info.float_storage);
  // Residuals are quantized by |POINT:SCALE| (half a step either way).
  ExpectSameTrajectories(written, read, 0.5 * std::abs(info.point_scale) + 1e-6);
}

TEST(C3dWriter, WritesAtomicallyAndReadsBackMetres) {
  MarkerTrajectories written = Synthetic(5, 9);
  ASSERT_TRUE(ConvertUnits(Metres(), &written).ok());
  const std::string path = mocapsolve::testing::TempPath("metres.c3d");
  Status status = WriteC3d(path, written);
  ASSERT_TRUE(status.ok()) << status.message();
  MarkerTrajectories read;
  C3dFileInfo info;
  status = ReadC3d(path, &read, &info);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(read.unit.name, "m");
  ExpectSameTrajectories(written, read, 0.5 * std::abs(info.point_scale) + 1e-9);
}

TEST(C3dWriter, MoreThan255LabelsGoToLabels2AndLabels3) {
  // 600 points: LABELS, LABELS2, LABELS3 (255 + 255 + 90), and long labels so that the
  // per-parameter size limit matters too.
  std::vector<std::string> labels;
  for (int m = 0; m < 600; ++m) {
    labels.push_back("Performer:marker_with_a_rather_long_descriptive_name_" + std::to_string(m));
  }
  MarkerTrajectories written(labels, 3);
  written.frame_rate = 60.0;
  written.unit = Millimetres();
  for (int f = 0; f < 3; ++f) {
    for (int m = 0; m < 600; ++m) {
      if (m % 97 != f) written.SetSample(f, m, Eigen::Vector3d(m, f, m + f + 0.5), 1.0f);
    }
  }
  const std::string bytes = Encode(written);
  EXPECT_NE(ParameterValueOffset(bytes, "LABELS2"), std::string::npos);
  EXPECT_NE(ParameterValueOffset(bytes, "LABELS3"), std::string::npos);
  MarkerTrajectories read;
  const Status status = ParseC3d(bytes, "many.c3d", &read);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(read.labels(), labels);
  EXPECT_EQ(read.valid_mask(), written.valid_mask());
  EXPECT_EQ(read.position(2, 599), Eigen::Vector3d(599, 2, 601.5));
}

TEST(C3dWriter, FrameNumbersBeyond16BitsSurviveViaTrialFields) {
  MarkerTrajectories written = Synthetic(2, 5);
  written.first_frame = 70000;
  MarkerTrajectories read;
  const Status status = ParseC3d(Encode(written), "late.c3d", &read);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(read.first_frame, 70000);
  EXPECT_EQ(read.num_frames(), 5);
}

TEST(C3dWriter, MissingIsWrittenAsInvalidNotAsZero) {
  MarkerTrajectories written(std::vector<std::string>{"A", "B"}, 1);
  written.frame_rate = 100.0;
  written.unit = Millimetres();
  written.SetSample(0, 0, Eigen::Vector3d(1, 2, 3));
  const std::string bytes = Encode(written);
  // Marker B of frame 0: zeros with residual word -1.
  const size_t data = (static_cast<std::uint8_t>(bytes[16]) - 1) * 512;
  float residual;
  std::memcpy(&residual, bytes.data() + data + 16 + 12, 4);
  EXPECT_EQ(residual, -1.0f);
  // Even with the all-zero rule off, B reads back missing.
  MarkerTrajectories read;
  C3dReadOptions keep_zeros;
  keep_zeros.zero_position_is_missing = false;
  ASSERT_TRUE(ParseC3d(bytes, "m.c3d", &read, nullptr, keep_zeros).ok());
  EXPECT_TRUE(read.valid(0, 0));
  EXPECT_FALSE(read.valid(0, 1));
}

TEST(C3dWriter, ValidSampleAtOriginReadsAsMissingUnlessAsked) {
  // The documented caveat of the all-zero rule.
  MarkerTrajectories written(std::vector<std::string>{"A"}, 1);
  written.frame_rate = 100.0;
  written.unit = Millimetres();
  written.SetSample(0, 0, Eigen::Vector3d::Zero());
  const std::string bytes = Encode(written);
  MarkerTrajectories read;
  C3dFileInfo info;
  ASSERT_TRUE(ParseC3d(bytes, "o.c3d", &read, &info).ok());
  EXPECT_FALSE(read.valid(0, 0));
  EXPECT_EQ(info.zero_position_samples, 1);
  C3dReadOptions keep_zeros;
  keep_zeros.zero_position_is_missing = false;
  ASSERT_TRUE(ParseC3d(bytes, "o.c3d", &read, nullptr, keep_zeros).ok());
  EXPECT_TRUE(read.valid(0, 0));
}

TEST(C3dWriter, RealFilesRoundTrip) {
  // Float C3D -> double -> float is exact, so positions of float files come back
  // bit-identical; int16 files (basketball) come back within float precision.
  for (const char* file : {"c3d/02_01.c3d", "c3d/nick_freeform_001.c3d",
                           "c3d/cmu_dribble_shoot_basketball.c3d"}) {
    MOCAPSOLVE_DATA_FILE(path, file);
    MarkerTrajectories original, read;
    ASSERT_TRUE(ReadC3d(path, &original).ok()) << file;
    const std::string copy = mocapsolve::testing::TempPath("copy.c3d");
    Status status = WriteC3d(copy, original);
    ASSERT_TRUE(status.ok()) << status.message();
    C3dFileInfo info;
    status = ReadC3d(copy, &read, &info);
    ASSERT_TRUE(status.ok()) << status.message();
    EXPECT_EQ(read.positions().cols(), original.positions().cols());
    EXPECT_EQ(read.valid_mask(), original.valid_mask()) << file;
    C3dFileInfo original_info;
    ASSERT_TRUE(ReadC3d(path, &original, &original_info).ok());
    for (Eigen::Index i = 0; i < read.positions().cols() && original_info.float_storage; ++i) {
      if (!original.valid_mask()[i]) continue;
      ASSERT_EQ(read.positions().col(i), original.positions().col(i)) << file << " sample " << i;
    }
    ExpectSameTrajectories(original, read,
                           0.5 * std::abs(info.point_scale) + 1e-5 /* float rounding */);
  }
}

TEST(C3dWriter, RejectsWhatC3dCannotHold) {
  std::string bytes;
  MarkerTrajectories no_rate = Synthetic(1, 1);
  no_rate.frame_rate = 0.0;
  ExpectOneLineError(EncodeC3d(no_rate, "out.c3d", &bytes), "out.c3d", "frame rate");
  MarkerTrajectories long_label(std::vector<std::string>{std::string(300, 'x')}, 1);
  long_label.frame_rate = 1.0;
  ExpectOneLineError(EncodeC3d(long_label, "out.c3d", &bytes), "out.c3d", "255");
  MarkerTrajectories huge = Synthetic(1, 1);
  huge.SetSample(0, 0, Eigen::Vector3d(1e300, 0, 0));
  ExpectOneLineError(EncodeC3d(huge, "out.c3d", &bytes), "out.c3d", "1e+300 is beyond +-1e+09");
}

// ---------------------------------------------------------------------------------------
// (e) Bad input: each a one-line error naming the file and the field or offset.

class C3dBadInput : public ::testing::Test {
 protected:
  void SetUp() override { good_ = Encode(Synthetic(3, 10)); }
  std::string good_;
  MarkerTrajectories t_;
};

TEST_F(C3dBadInput, TheUncorruptedFileParses) {
  const Status status = Parse(good_, &t_);
  ASSERT_TRUE(status.ok()) << status.message();
  EXPECT_EQ(t_.num_frames(), 10);
}

TEST_F(C3dBadInput, TruncatedHeader) {
  ExpectOneLineError(Parse(good_.substr(0, 300), &t_), "bad.c3d", "512-byte");
  ExpectOneLineError(Parse("", &t_), "bad.c3d", "512-byte");
}

TEST_F(C3dBadInput, TruncatedParameterSection) {
  ExpectOneLineError(Parse(good_.substr(0, 512 + 40), &t_), "bad.c3d", "past the end");
}

TEST_F(C3dBadInput, TruncatedData) {
  const size_t data = (static_cast<std::uint8_t>(good_[16]) - 1) * 512;
  ExpectOneLineError(Parse(good_.substr(0, data + 100), &t_), "bad.c3d", "do not fit");
}

TEST_F(C3dBadInput, ParameterPointerBeyondTheFile) {
  std::string bytes = good_;
  bytes[0] = static_cast<char>(200);
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "header byte 0");
  bytes[0] = 1;  // The header itself.
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "header byte 0");
}

TEST_F(C3dBadInput, DataStartBeyondTheFile) {
  std::string bytes = good_;
  PutU16(&bytes, ParameterValueOffset(bytes, "DATA_START"), 5000);
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "POINT:DATA_START");
  // Pointing into the parameter section is no better.
  PutU16(&bytes, ParameterValueOffset(bytes, "DATA_START"), 2);
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "POINT:DATA_START");
}

TEST_F(C3dBadInput, FrameCountLargerThanTheData) {
  std::string bytes = good_;
  PutU16(&bytes, 8, 17 + 1000);  // Header last frame.
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "frames 17..1017");
  // The 32-bit TRIAL fields are checked as well (here claiming 2^31 frames).
  bytes = good_;
  const size_t end_field = ParameterValueOffset(bytes, "ACTUAL_END_FIELD");
  PutU16(&bytes, end_field + 2, 0x7fff);
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "TRIAL:ACTUAL_START_FIELD");
}

// Frames of no points take no bytes, so the data cannot bound their count: kMaxFrames
// does (2^31 - 1 of them crashed convert, corrupt and view with bad_alloc).
TEST_F(C3dBadInput, NoPointsAndAHugeTrialFrameCountIsRefused) {
  MarkerTrajectories empty(std::vector<std::string>{}, 3);
  empty.frame_rate = 100.0;
  std::string bytes = Encode(empty);
  ASSERT_TRUE(Parse(bytes, &t_).ok());
  EXPECT_EQ(t_.num_frames(), 3);
  PutU16(&bytes, ParameterValueOffset(bytes, "ACTUAL_END_FIELD") + 2, 0x7fff);
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "a take may have");
  PutU16(&bytes, ParameterValueOffset(bytes, "ACTUAL_END_FIELD") + 2, 0xffff);
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "no valid frame count");
}

TEST_F(C3dBadInput, BadProcessorByte) {
  std::string bytes = good_;
  bytes[512 + 3] = 90;
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "processor type");
}

TEST_F(C3dBadInput, NotAC3dFile) {
  std::string bytes = good_;
  bytes[1] = 0x42;
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "not a C3D file");
}

TEST_F(C3dBadInput, ParameterLinksThatGoBackwardsOrNowhere) {
  std::string bytes = good_;
  // The first record is the POINT group: name length at 516, link after the name.
  const size_t link = 512 + 4 + 2 + 5;
  PutU16(&bytes, link, static_cast<std::uint16_t>(-8));
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "backwards");
  PutU16(&bytes, link, 30000);  // Far past the end.
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "past the end");
}

TEST_F(C3dBadInput, HugeParameterDimensions) {
  std::string bytes = good_;
  const size_t labels = ParameterValueOffset(bytes, "LABELS");
  bytes[labels - 2] = static_cast<char>(255);  // width
  bytes[labels - 1] = static_cast<char>(255);  // count
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "past the end");
}

TEST_F(C3dBadInput, PointUsedDisagreesWithHeader) {
  std::string bytes = good_;
  PutU16(&bytes, ParameterValueOffset(bytes, "USED"), 4);
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "POINT:USED");
}

TEST_F(C3dBadInput, AnalogCountDisagreesWithAnalogUsed) {
  std::string bytes = good_;
  PutU16(&bytes, ParameterValueOffset(bytes, "USED", /*skip=*/1), 4);  // ANALOG:USED
  PutU16(&bytes, 4, 10);                                                // header word 3
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "ANALOG:USED 4");
  // A consistent count is skipped: 8 values per frame then no longer fit the data.
  PutU16(&bytes, 4, 8);
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "do not fit");
}

TEST_F(C3dBadInput, ZeroScale) {
  std::string bytes = good_;
  const size_t scale = ParameterValueOffset(bytes, "SCALE");
  std::memset(&bytes[scale], 0, 4);
  ExpectOneLineError(Parse(bytes, &t_), "bad.c3d", "POINT:SCALE");
}

TEST_F(C3dBadInput, NoCorruptionCrashesOrHangs) {
  // Every truncation and a few thousand random byte corruptions: any Status is fine,
  // crashing, hanging or a failed allocation is not (run under the sanitizer build too).
  for (size_t length = 0; length < good_.size(); length += 7) {
    (void)Parse(good_.substr(0, length), &t_);
  }
  std::mt19937 rng(7);
  const size_t header_and_parameters = (static_cast<std::uint8_t>(good_[16]) - 1) * 512;
  for (int trial = 0; trial < 3000; ++trial) {
    std::string bytes = good_;
    // Mostly the structure, sometimes anywhere (the samples themselves).
    const size_t range = trial % 4 == 0 ? bytes.size() : header_and_parameters;
    for (int k = 0; k < 4; ++k) bytes[rng() % range] = static_cast<char>(rng() & 0xff);
    const Status status = Parse(bytes, &t_);
    if (!status.ok()) {
      ASSERT_EQ(status.message().find('\n'), std::string::npos) << status.message();
    } else {
      // Whatever decoded must still obey the mask invariant.
      for (Eigen::Index i = 0; i < t_.positions().cols(); ++i) {
        ASSERT_EQ(t_.valid_mask()[i] != 0, t_.positions().col(i).allFinite());
      }
    }
  }
}

TEST(C3dBadInputRealFile, CorruptedDecIntFileWithAnalogNeverCrashes) {
  // DEC, int16 storage, analog data: the paths our (Intel float) writer cannot produce.
  MOCAPSOLVE_DATA_FILE(path, "c3d/c3d.org_sample01/Eb015vi.c3d");
  std::string good;
  ASSERT_TRUE(ReadFileToString(path, &good).ok());
  MarkerTrajectories t;
  std::mt19937 rng(11);
  const size_t structure = 11 * 512;  // Header and parameter blocks (data starts at 11).
  for (int trial = 0; trial < 300; ++trial) {
    std::string bytes = good;
    for (int k = 0; k < 3; ++k) bytes[rng() % structure] = static_cast<char>(rng() & 0xff);
    if (trial % 10 == 0) bytes.resize(rng() % bytes.size());
    const Status status = ParseC3d(bytes, "Eb015vi.c3d", &t);
    if (!status.ok()) {
      ASSERT_EQ(status.message().find('\n'), std::string::npos) << status.message();
    }
  }
}

TEST(C3dBadFiles, HandmadeBadFilesFailWithOneLine) {
  // bad_c3d_analog_used_huge.c3d: found by the c3d fuzzer (UBSan: a float ANALOG:USED of
  // -4e34 cast to int); bad_c3d_data_start_negative.c3d likewise (a float POINT:DATA_START
  // of -1.07e8 cast to uint64). Every count parameter is now checked as a whole number
  // 0..65535 in one place.
  for (const char* name : {"bad_processor.c3d", "bad_truncated.c3d", "bad_data_start.c3d",
                           "bad_c3d_analog_used_huge.c3d", "bad_c3d_data_start_negative.c3d"}) {
    const std::string path = mocapsolve::testing::SourcePath(std::string("tests/data/bad/") + name);
    MarkerTrajectories t;
    const Status status = ReadC3d(path, &t);
    ASSERT_FALSE(status.ok()) << name;
    EXPECT_EQ(status.message().find('\n'), std::string::npos) << status.message();
    EXPECT_NE(status.message().find(name), std::string::npos) << status.message();
    EXPECT_EQ(status.message().find("cannot open"), std::string::npos) << status.message();
    std::printf("%s\n", status.message().c_str());
  }
}

TEST(C3dReader, MissingFileIsAnError) {
  MarkerTrajectories t;
  ExpectOneLineError(ReadC3d("/nonexistent/x.c3d", &t), "/nonexistent/x.c3d", "cannot open");
}

}  // namespace
}  // namespace mocapsolve
