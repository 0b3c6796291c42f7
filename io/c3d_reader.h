// C3D reader: marker (POINT) data of a C3D file into MarkerTrajectories.
//
// File layout (512-byte blocks, numbered from 1):
//   block 1           header. Byte 0 = block of the parameter section, byte 1 = 0x50.
//                     16-bit words (1-based): 2 #points, 3 analog values per frame,
//                     4/5 first/last frame, 7-8 POINT:SCALE (float), 9 data start
//                     block, 11-12 frame rate (float).
//   parameter block   4-byte header whose byte 3 (0-based) is the processor type:
//                     84 Intel (little-endian IEEE), 85 DEC/VAX, 86 SGI/MIPS
//                     (big-endian IEEE). Then group and parameter records, each linked
//                     to the next by a signed 16-bit offset.
//   data start block  frame after frame: #points x (x, y, z, residual word), then the
//                     frame's analog values (skipped here).
// Byte order follows the processor type for every integer and float, header included.
// DEC floats are VAX F-floats: swap the two 16-bit words, read little-endian IEEE,
// divide by 4 (header bytes f0 43 00 00 -> 120.0). DEC integers are little-endian.
//
// Storage and scale: POINT:SCALE > 0 means int16 samples, coordinate = word * SCALE;
// POINT:SCALE < 0 means float samples, used as stored (|SCALE| still scales the
// residual). Coordinates are in POINT:UNITS.
//
// The residual word: as int16 (float storage: the float converted to an integer and
// taken as its low 16 bits, so the 65535.0 some writers use reads as -1), high byte =
// camera mask (bits 8-14), low byte = residual / |SCALE|. A negative word means the
// sample is invalid -> missing. A fractional float residual is truncated to its integer
// part before this decoding, as the C3D specification requires.
// All-zero samples: a sample at exactly (0,0,0) with a non-negative residual is also
// read as missing (C3dReadOptions::zero_position_is_missing, default on): older
// writers mark gaps that way, and a real marker at the origin to the last bit is not
// plausible. This matches the data README's count "invalid = negative residual or
// all-zero". The JA1Gait35 file's one zero sample carries residual 65535.0 (= -1), so
// it is missing under both rules.
//
// Which value wins when header and parameters both say it:
//   points per frame   header word 2; POINT:USED must agree (error otherwise).
//   frames             header words 4-5; TRIAL:ACTUAL_START_FIELD/ACTUAL_END_FIELD
//                      (two 16-bit words, low first) when the header cannot hold them
//                      (> 65535).
//   scale, rate        POINT:SCALE, POINT:RATE; the header's when absent.
//   data start         POINT:DATA_START (unsigned); the header's when absent.
//   analog per frame   header word 3 (values skipped after each frame's points); it must
//                      be a multiple of ANALOG:USED.
//   labels             POINT:LABELS, LABELS2, LABELS3, ... concatenated (more than 255
//                      points); blanks trimmed at both ends; points without a label are named
//                      "*<n>" (1-based, the Vicon convention for unlabelled points).
// Subject prefixes come from SUBJECTS:LABEL_PREFIXES (empty entries dropped); labels
// are kept raw, see marker_trajectories.h.
// Which points are markers: duplicate labels numbered (RKNE, RKNE#2), one subject chosen
// from a file of several, model outputs (POINT:ANGLES, ..., Plug-in Gait virtual points)
// set apart in MarkerTrajectories::model_outputs: the rules are in c3d_points.h.
//
// Hostile files: the parameter pointer, every parameter record, the data start and
// frames x frame size are checked against the file size before anything is read or
// allocated, and parameter records must move forward, so a bad file gives a Status
// naming the file and the field or byte offset, never a crash, hang or huge allocation.
#ifndef MOCAPSOLVE_IO_C3D_READER_H_
#define MOCAPSOLVE_IO_C3D_READER_H_

#include <string>
#include <string_view>
#include <vector>

#include "kinematics/marker_trajectories.h"
#include "kinematics/status.h"

namespace mocapsolve {

enum class C3dProcessor { kIntel = 84, kDec = 85, kSgiMips = 86 };

struct C3dReadOptions {
  // Read an exactly (0,0,0) sample with a non-negative residual as missing.
  bool zero_position_is_missing = true;
  // Read model outputs (c3d_points.h) as markers instead of setting them apart.
  bool include_model_outputs = false;
  // The subject whose points are read, its prefix stripped ("Daphnee", "Daphnee:" or a
  // SUBJECTS:NAMES entry); "" = the file's only subject, or of several the preferred one
  // below when the file has it, else the one with the most points (with a warning).
  std::string subject_prefix;
  std::string preferred_subject_prefix;
  // Read the header and parameters only: the labels, rate and unit, no samples (the
  // trajectories have 0 frames; C3dFileInfo::frames gives the file's count). For an
  // estimate of a take's size before any work (io/marker_file.h: ReadMarkerFileShape).
  bool header_only = false;
};

// What the reader found, for reports and tests.
struct C3dFileInfo {
  C3dProcessor processor = C3dProcessor::kIntel;
  bool float_storage = false;
  double point_scale = 0.0;          // POINT:SCALE as stored (negative = float storage).
  int parameter_block = 0;           // 1-based.
  int data_start_block = 0;          // 1-based.
  int analog_values_per_frame = 0;   // Header word 3: analog samples skipped per frame.
  int analog_channels = 0;           // ANALOG:USED (0 when absent).
  int frames = 0;                    // Frames in the file (also with header_only).
  int negative_residual_samples = 0; // Missing: negative residual word (or NaN coordinates).
  int zero_position_samples = 0;     // Missing because they were exactly (0,0,0).
  int model_output_points = 0;       // Points set apart as model outputs.
  int other_subject_points = 0;      // Points of the subjects not chosen (not read).
  std::vector<std::string> warnings; // One line each, naming the file (duplicate labels, ...).
};

// Reads the file at path. *info is optional.
Status ReadC3d(const std::string& path, MarkerTrajectories* trajectories,
               C3dFileInfo* info = nullptr, const C3dReadOptions& options = {});

// Decodes a C3D image held in memory; file_name only labels error messages.
Status ParseC3d(std::string_view bytes, const std::string& file_name,
                MarkerTrajectories* trajectories, C3dFileInfo* info = nullptr,
                const C3dReadOptions& options = {});

}  // namespace mocapsolve

#endif  // MOCAPSOLVE_IO_C3D_READER_H_
