// libFuzzer target: AMC text through ParseAmc, against a fixed small ASF skeleton.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "io/amc_reader.h"
#include "io/asf_reader.h"

namespace {

struct AsfSkeleton {
  mocapsolve::Skeleton skeleton;
  mocapsolve::AsfInfo info;
};

const AsfSkeleton& Fixed() {
  static const AsfSkeleton* fixed = [] {
    static const char kAsf[] =
        ":version 1.10\n:name fuzz\n:units\n  mass 1.0\n  length 0.45\n  angle deg\n:root\n"
        "   order TX TY TZ RX RY RZ\n   axis XYZ\n   position 0 0 0\n   orientation 0 0 0\n"
        ":bonedata\n  begin\n     id 1\n     name hip\n     direction 1 0 0\n     length 2\n"
        "     axis 0 0 0 XYZ\n  end\n  begin\n     id 2\n     name thigh\n     direction 0 -1 0\n"
        "     length 7\n     axis 0 0 20 XYZ\n    dof rx ry rz\n    limits (-160.0 20.0)\n"
        "           (-70.0 70.0)\n           (-60.0 70.0)\n  end\n:hierarchy\n  begin\n"
        "    root hip\n    hip thigh\n  end\n";
    auto* out = new AsfSkeleton;
    if (!mocapsolve::ParseAsf(kAsf, "fuzz.asf", &out->skeleton, &out->info).ok()) std::abort();
    return out;
  }();
  return *fixed;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const AsfSkeleton& fixed = Fixed();
  mocapsolve::Motion motion;
  (void)mocapsolve::ParseAmc(std::string(reinterpret_cast<const char*>(data), size), "fuzz.amc",
                             fixed.skeleton, fixed.info, 120.0, &motion);
  return 0;
}
