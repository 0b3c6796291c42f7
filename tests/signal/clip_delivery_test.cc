// signal/clip_delivery.h: ranges resolved against a clip (and their messages), resampling
// (the clip's own rate gives its frames back, rotations take the short way round even
// when stored with opposite signs), and settings/delivery_settings.h's parsing of A:B.
#include "signal/clip_delivery.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "settings/delivery_settings.h"

namespace mocapsolve {
namespace {

std::string Message(const Status& status) { return status.ok() ? "ok" : status.message(); }

// Two joints; frame k at `rate`: root at (k, 2k, 0), joint 1 turned 10 k degrees about Y,
// stored with alternating signs (q and -q are the same rotation).
Motion TurningClip(int frames, double rate) {
  Motion motion;
  motion.frame_rate = rate;
  for (int k = 0; k < frames; ++k) {
    Pose pose;
    pose.translations = {Eigen::Vector3d(k, 2.0 * k, 0), Eigen::Vector3d(0, 1, 0)};
    Eigen::Quaterniond q(Eigen::AngleAxisd(10.0 * k * M_PI / 180.0, Eigen::Vector3d::UnitY()));
    if (k % 2 == 1) q.coeffs() = -q.coeffs();
    pose.rotations = {Eigen::Quaterniond::Identity(), q};
    motion.frames.push_back(pose);
  }
  return motion;
}

double AngleAboutYDeg(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d x = q * Eigen::Vector3d::UnitX();
  return std::atan2(-x.z(), x.x()) * 180.0 / M_PI;
}

TEST(ClipDelivery, TheClipsOwnRateGivesItsFramesBack) {
  const Motion clip = TurningClip(9, 30.0);
  Motion same;
  ASSERT_EQ(Message(ResampleMotion(clip, 30.0, &same)), "ok");
  ASSERT_EQ(same.num_frames(), 9);
  for (int k = 0; k < 9; ++k) {
    EXPECT_EQ(same.frames[k].translations[0], clip.frames[k].translations[0]);
    EXPECT_EQ(same.frames[k].rotations[1].coeffs(), clip.frames[k].rotations[1].coeffs());
  }
  // 120 -> 30: every fourth frame, exactly; the last one kept (1 s: 121 -> 31 frames).
  const Motion fast = TurningClip(121, 120.0);
  Motion slow;
  ASSERT_EQ(Message(ResampleMotion(fast, 30.0, &slow)), "ok");
  ASSERT_EQ(slow.num_frames(), 31);
  EXPECT_EQ(slow.frame_rate, 30.0);
  for (int k = 0; k < 31; ++k) EXPECT_EQ(slow.frames[k].translations[0], fast.frames[4 * k].translations[0]) << k;
  // A clip that does not end on an output frame stops before its end (no extrapolation).
  Motion short_clip = TurningClip(10, 120.0), resampled;  // 0.075 s.
  ASSERT_EQ(Message(ResampleMotion(short_clip, 30.0, &resampled)), "ok");
  EXPECT_EQ(resampled.num_frames(), 3);  // 0, 1/30, 2/30 s.
}

TEST(ClipDelivery, BetweenFramesTranslationsLinearlyRotationsTheShortWay) {
  const Motion clip = TurningClip(5, 30.0);
  Motion doubled;
  ASSERT_EQ(Message(ResampleMotion(clip, 60.0, &doubled)), "ok");
  ASSERT_EQ(doubled.num_frames(), 9);
  for (int k = 0; k < 9; ++k) {
    EXPECT_NEAR((doubled.frames[k].translations[0] - Eigen::Vector3d(k / 2.0, k, 0)).norm(), 0.0, 1e-12) << k;
    // 5 degrees a frame at 60 fps, though every other source frame holds -q.
    EXPECT_NEAR(AngleAboutYDeg(doubled.frames[k].rotations[1]), 5.0 * k, 1e-9) << k;
    EXPECT_NEAR(doubled.frames[k].rotations[1].norm(), 1.0, 1e-12);
  }
  // 24 -> 30 fps: time 1/30 s lies at 0.8 of the first interval.
  Motion film = TurningClip(25, 24.0), video;
  ASSERT_EQ(Message(ResampleMotion(film, 30.0, &video)), "ok");
  EXPECT_EQ(video.num_frames(), 31);
  EXPECT_NEAR(AngleAboutYDeg(video.frames[1].rotations[1]), 8.0, 1e-9);
  EXPECT_NEAR(video.frames[1].translations[0].x(), 0.8, 1e-12);
  EXPECT_EQ(Message(ResampleMotion(film, 0.0, &video)), "resample: the rate must be positive, got 0");
  EXPECT_EQ(Message(ResampleMotion(film, 1e12, &video)),
            "resample: 1e+12 fps would make more than 10^7 frames of a 1 s clip");
}

ClipDelivery Parsed(const std::string& frames, const std::string& seconds, double out_fps = 0.0) {
  DeliverySettings settings;
  settings.frames = frames;
  settings.seconds = seconds;
  settings.out_fps = out_fps;
  ClipDelivery delivery;
  const Status status = ClipDeliveryFromSettings(settings, &delivery);
  EXPECT_TRUE(status.ok()) << status.message();
  return delivery;
}

std::string ParseError(const std::string& frames, const std::string& seconds) {
  DeliverySettings settings;
  settings.frames = frames;
  settings.seconds = seconds;
  ClipDelivery delivery;
  return Message(ClipDeliveryFromSettings(settings, &delivery));
}

TEST(ClipDelivery, RangesAreCheckedAgainstTheClip) {
  int first = -1, last = -1;
  EXPECT_EQ(Message(ResolveClipRange(Parsed("10:20", "").range, 61, 120.0, &first, &last)), "ok");
  EXPECT_EQ(first, 10);
  EXPECT_EQ(last, 20);
  EXPECT_EQ(Message(ResolveClipRange(Parsed("50:", "").range, 61, 120.0, &first, &last)), "ok");
  EXPECT_EQ(first, 50);
  EXPECT_EQ(last, 60);
  EXPECT_EQ(Message(ResolveClipRange(Parsed(":0", "").range, 61, 120.0, &first, &last)), "ok");
  EXPECT_EQ(last, 0);
  // Seconds: the frames whose times lie in [A, B], a bound on a frame's time keeping it.
  EXPECT_EQ(Message(ResolveClipRange(Parsed("", "0.1:0.2").range, 61, 120.0, &first, &last)), "ok");
  EXPECT_EQ(first, 12);
  EXPECT_EQ(last, 24);
  EXPECT_EQ(Message(ResolveClipRange(Parsed("", "0.105:").range, 61, 120.0, &first, &last)), "ok");
  EXPECT_EQ(first, 13);
  EXPECT_EQ(last, 60);
  EXPECT_EQ(Message(ResolveClipRange(Parsed("10:61", "").range, 61, 120.0, &first, &last)),
            "--frames=10:61: the clip has 61 frames, 0:60");
  EXPECT_EQ(Message(ResolveClipRange(Parsed("", "0.2:0.6").range, 61, 120.0, &first, &last)),
            "--seconds=0.2:0.6: the clip lasts 0.5 s, 0:0.5");
  EXPECT_EQ(Message(ResolveClipRange(Parsed("", "0.101:0.102").range, 61, 120.0, &first, &last)),
            "--seconds=0.101:0.102: holds no frame (the first is after the last)");
  // Malformed ranges: one line naming the option.
  EXPECT_EQ(ParseError("3-9", ""),
            "--frames: expected A:B (first and last frame, whole numbers >= 0; either may be left out), got '3-9'");
  for (const char* bad : {"1.5:3", "-1:3", "1:2:3", "a:b", "0x10:20", "1e40:"}) {
    EXPECT_EQ(ParseError(bad, "").rfind("--frames: expected A:B", 0), 0u) << bad;
  }
  for (const char* bad : {"1", "nan:2", "-0.5:1", "inf:"}) {
    EXPECT_EQ(ParseError("", bad).rfind("--seconds: expected A:B", 0), 0u) << bad;
  }
  EXPECT_EQ(ParseError("9:3", ""), "--frames: the first end is after the last in '9:3'");
  EXPECT_EQ(ParseError("1:3", "0:1"), "--frames and --seconds: give one range, not both");
}

TEST(ClipDelivery, CutThenResampled) {
  const Motion clip = TurningClip(121, 120.0);
  Motion out;
  ASSERT_EQ(Message(DeliverClip(clip, Parsed("", "0.5:1", 30.0), &out)), "ok");
  ASSERT_EQ(out.num_frames(), 16);  // 0.5 s at 30 fps.
  for (int k = 0; k < 16; ++k) EXPECT_EQ(out.frames[k].translations[0], clip.frames[60 + 4 * k].translations[0]);
  // Nothing asked: the clip as it is.
  ASSERT_EQ(Message(DeliverClip(clip, ClipDelivery(), &out)), "ok");
  EXPECT_EQ(out.num_frames(), 121);
  EXPECT_EQ(out.frame_rate, 120.0);
}

}  // namespace
}  // namespace mocapsolve
