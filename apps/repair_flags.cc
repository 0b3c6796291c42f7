#include "apps/repair_flags.h"

#include <gflags/gflags.h>

#include "apps/solver_flags.h"

namespace {
// The flags' defaults are the settings' (settings/repair_settings.h): one source.
const mocapsolve::RepairSettings kDefault;
}  // namespace

DEFINE_double(dp_max_cm, kDefault.dp_max_cm, "A joint farther than this (cm) from the robust reference is bad "
              "(thesis 3.4.2: 10 cm).");
DEFINE_double(dr_max_deg, kDefault.dr_max_deg, "A joint turned more than this (degrees) from the reference is bad "
              "(thesis: 30).");
DEFINE_double(outlier_cm, kDefault.outlier_cm, "With --outliers=fixed, a marker sample farther than this (cm) from its "
              "reconstruction on the reference is an outlier (chapter 3's rule); with robust, the cap "
              "of every marker's gate.");
DEFINE_string(outliers, kDefault.outliers.c_str(), "How outliers are found: robust (each marker judged against its own "
              "typical residual over the take: gate = median deviation + --outlier_mads MADs, at "
              "least --outlier_min_cm, at most --outlier_cm; finds 1-4 cm jumps on markers that are "
              "normally within mm and spares markers on loose tissue or with an offset error) | fixed "
              "(--outlier_cm from the reconstruction).");
DEFINE_double(outlier_mads, kDefault.outlier_mads, "Robust outlier gate: robust standard deviations (1.4826 MAD) "
              "past the marker's median deviation.");
DEFINE_double(outlier_min_cm, kDefault.outlier_min_cm, "Robust outlier gate: never below this (cm).");
DEFINE_bool(undo_swaps, kDefault.undo_swaps, "Find label swaps (a sample far from its own marker's prediction and "
            "close to that of a nearby marker left without a good sample) and relabel them "
            "instead of cutting and refilling; reported as 'swaps'.");
DEFINE_double(swap_radius_cm, kDefault.swap_radius_cm, "Markers whose predicted positions are this close (cm) may "
              "swap labels.");
DEFINE_int32(swap_min_frames, kDefault.swap_min_frames, "A swap must persist this many consecutive frames.");
DEFINE_bool(assign_unlabelled, kDefault.assign_unlabelled, "Label unlabelled points (C3D '*52'): a point becomes the "
            "sample of a missing marker where it lies within the marker's gate around its prediction "
            "and continues the marker's track, one to one per frame; reported as 'unlabelled_assigned'.");
DEFINE_double(unlabelled_min_cm, kDefault.unlabelled_min_cm, "Unlabelled assignment gate (the marker's median deviation + "
              "--outlier_mads MADs): never below this (cm).");
DEFINE_double(unlabelled_max_cm, kDefault.unlabelled_max_cm, "Unlabelled assignment gate: never above this (cm).");
DEFINE_int32(unlabelled_min_frames, kDefault.unlabelled_min_frames, "An assigned run of frames that continues no observed "
             "sample of the marker needs at least this many frames.");
DEFINE_int32(trim_max, kDefault.trim_max, "Frames trimmed at most on each side of a gap (thesis: 120).");
DEFINE_int32(small_track, kDefault.small_track, "Valid runs of at most this many frames between gaps are dropped.");
DEFINE_int32(small_gap, kDefault.small_gap, "Gaps of at most this many frames are filled by a plain cubic.");
DEFINE_double(vel_clamp, kDefault.vel_clamp, "Clamp of the offset velocity at gap edges, in cm per frame "
              "(the thesis' 0.25; its unit is not stated, its data are in cm).");
DEFINE_int32(edge_samples, kDefault.edge_samples, "Samples beyond each gap edge that the refill's offset velocity is "
             "fitted to (a least-squares line; 2 = the thesis' one-sided difference, which a jittery "
             "marker throws off; 1 = no offset velocity: the fill blends the two edge offsets, "
             "which measured best on real takes, BENCHMARKS.md).");
DEFINE_string(fill, kDefault.fill.c_str(), "How a gap is filled from the reference X^: kriging (the offset from "
              "X^ modelled per marker as mean + exponentially correlated process + white noise, "
              "estimated from the take; the fill is its conditional mean given --fill_samples samples "
              "on each side) | blend (X^ plus a blend from one edge's offset to the other's, Algorithm 3).");
DEFINE_int32(fill_samples, kDefault.fill_samples, "--fill=kriging: offset samples conditioned on per gap side.");
DEFINE_bool(refit_reference, kDefault.refit_reference, "With --reference=tracker: refit X^ without the samples found "
            "bad (it leaned toward them) and fill smooth bad runs (fly-off, ghost) and gaps from it; "
            "rough runs (noise, jitter) are filled from X^ as solved.");
DEFINE_double(refit_rough_factor, kDefault.refit_rough_factor, "A bad run is rough when its median |second "
              "difference| exceeds this many times the marker's own.");
DEFINE_double(rough_extension_factor, kDefault.rough_extension_factor, "A rough bad run is extended over the "
              "samples beside it whose residual |second difference| exceeds this many times the marker's "
              "median and a tenth of the gates' floor (a noise run cut whole; at most --trim_max per side; "
              "0: off).");
DEFINE_string(reference, kDefault.reference.c_str(), "The robust reference Y^: tracker (frame by frame, robust loss, "
              "pulled toward the previous frame; runs beside the naive solve) | clip (the "
              "whole-clip solve with a robust loss and smoothness; ~10x slower).");
DEFINE_string(reference_loss, kDefault.reference_loss.c_str(), "Robust loss of the reference solve: cauchy | huber.");
DEFINE_double(reference_loss_cm, kDefault.reference_loss_cm, "Where the reference solve's loss bends (cm).");
DEFINE_double(tracker_prior_weight, kDefault.tracker_prior_weight, "Tracker reference: pull of each joint rotation toward "
              "the previous frame, mm per radian (the naive solve's is --prior_weight).");
DEFINE_double(tracker_translation_prior, kDefault.tracker_translation_prior, "Tracker reference: pull of the root translation "
              "toward the previous frame (residual per unit of displacement).");

DEFINE_double(tracker_function_tolerance, kDefault.tracker_function_tolerance, "Tracker reference: stop when the relative cost "
              "change is below this. The reference only has to show where the markers broke: on "
              "02_01 1e-4 instead of 1e-6 leaves the repaired solve as good (0.170 vs 0.176 cm) and "
              "makes repair 1.6x faster.");

namespace mocapsolve {

RepairSettings RepairSettingsFromFlags() {
  RepairSettings s;
  s.dp_max_cm = FLAGS_dp_max_cm;
  s.dr_max_deg = FLAGS_dr_max_deg;
  s.outlier_cm = FLAGS_outlier_cm;
  s.outliers = FLAGS_outliers;
  s.outlier_mads = FLAGS_outlier_mads;
  s.outlier_min_cm = FLAGS_outlier_min_cm;
  s.undo_swaps = FLAGS_undo_swaps;
  s.swap_radius_cm = FLAGS_swap_radius_cm;
  s.swap_min_frames = FLAGS_swap_min_frames;
  s.assign_unlabelled = FLAGS_assign_unlabelled;
  s.unlabelled_min_cm = FLAGS_unlabelled_min_cm;
  s.unlabelled_max_cm = FLAGS_unlabelled_max_cm;
  s.unlabelled_min_frames = FLAGS_unlabelled_min_frames;
  s.trim_max = FLAGS_trim_max;
  s.small_track = FLAGS_small_track;
  s.small_gap = FLAGS_small_gap;
  s.vel_clamp = FLAGS_vel_clamp;
  s.edge_samples = FLAGS_edge_samples;
  s.fill = FLAGS_fill;
  s.fill_samples = FLAGS_fill_samples;
  s.refit_reference = FLAGS_refit_reference;
  s.refit_rough_factor = FLAGS_refit_rough_factor;
  s.rough_extension_factor = FLAGS_rough_extension_factor;
  s.reference = FLAGS_reference;
  s.reference_loss = FLAGS_reference_loss;
  s.reference_loss_cm = FLAGS_reference_loss_cm;
  s.tracker_prior_weight = FLAGS_tracker_prior_weight;
  s.tracker_translation_prior = FLAGS_tracker_translation_prior;
  s.tracker_function_tolerance = FLAGS_tracker_function_tolerance;
  return s;
}

Status RepairOptionsFromFlags(const Skeleton& skeleton, RepairOptions* options) {
  return RepairOptionsFromSettings(RepairSettingsFromFlags(), SolverSettingsFromFlags(), skeleton, options);
}

}  // namespace mocapsolve
