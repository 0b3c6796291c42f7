// loop_markers IN.c3d|.trc N OUT.c3d|.trc: the take repeated N times (frame f of the
// output is frame f mod #F of the input, every sample as it was), for measuring how a
// command's memory and time grow with the length of a take (bench/pipeline_memory.sh).
#include <cstdio>
#include <cstdlib>
#include <string>

#include "io/marker_file.h"

int main(int argc, char** argv) {
  using namespace mocapsolve;
  if (argc != 4 || std::atoi(argv[2]) < 1) {
    std::fprintf(stderr, "usage: loop_markers IN.c3d N OUT.c3d\n");
    return 1;
  }
  MarkerTrajectories in;
  Status status = ReadMarkerFile(argv[1], &in);
  if (!status.ok()) {
    std::fprintf(stderr, "%s\n", status.message().c_str());
    return 1;
  }
  const int repeats = std::atoi(argv[2]);
  MarkerTrajectories out(in.labels(), in.num_frames() * repeats);
  out.frame_rate = in.frame_rate;
  out.unit = in.unit;
  out.first_frame = in.first_frame;
  out.subject_prefixes = in.subject_prefixes;
  for (int f = 0; f < out.num_frames(); ++f) {
    const int g = f % in.num_frames();
    for (int m = 0; m < in.num_markers(); ++m) {
      if (in.valid(g, m)) out.SetSample(f, m, in.position(g, m), in.residual(g, m), in.camera_mask(g, m));
    }
  }
  status = WriteMarkerFile(argv[3], out);
  if (!status.ok()) {
    std::fprintf(stderr, "%s\n", status.message().c_str());
    return 1;
  }
  return 0;
}
