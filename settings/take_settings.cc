#include "settings/take_settings.h"

namespace mocapsolve {

const OptionGroup<TakeSettings>& TakeSettingOptions() {
  using S = TakeSettings;
  static const OptionGroup<S>* const group = &(*new OptionGroup<S>())
      .Add(&S::take_name, "take_name",
           "The take's name: the characters' new animation (default: the marker file's name without extension).")
      .Add(&S::filter_levels, "filter_levels", "levels",
           "Filter the solved motion: drop the N finest bands of its Laplacian pyramid (as `filter --levels=N`); "
           "0 = no filtering.")
      .Add(&S::label, "label",
           "Label the take's points first, as `mocapsolve label` does (raw or unlabelled captures; the label "
           "options set how): auto when the file lacks some of the subject's labels, always (the file's labels "
           "ignored), never (a label the file lacks is an error).",
           {"auto", "never", "always"})
      .Add(&S::window_frames, "window_frames", "frames",
           "A take of more frames than this runs window by window (each window's frames solved, repaired and "
           "retargeted on their own, its files written as the windows finish), so its memory is bounded by the "
           "window, not the take (about 28 MB + 11 KB per window frame, and 2.4 KB per frame of the take for the "
           "outputs); a take of at most this many frames runs whole, as before. 18,000 = 2.5 min at 120 Hz.",
           10, 2147483647)
      .Add(&S::window_context_frames, "window_context_frames", "frames",
           "A windowed take's context: each window also solves this many frames on each side of its own, "
           "and keeps only its own. The repair's reference and Hermite blends and its gap fills read the samples "
           "on both sides of a gap (--fill_samples a side), and the window's first solves, started from the "
           "previous window's solve, settle within it: 600 (5 s at 120 Hz) holds a 4 s gap's fill inside the "
           "context.",
           0, 1000000)
      .Add(&S::window_seam_blend_frames, "window_seam_blend_frames", "frames",
           "A windowed take's solve and characters cross-fade from one window's motion to the next over this "
           "many frames on each side of the seam (both windows solve those frames; a joint no marker moves, and "
           "a retarget's feet, can differ between them by centimetres, which joined edge to edge would pop in "
           "one frame); 0 joins them edge to edge. At most the context each side.",
           0, 1000000);
  return *group;
}

}  // namespace mocapsolve
