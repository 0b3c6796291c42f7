// Multiresolution filtering (signal/): Laplacian pyramids of numpy signals, filtering
// and band editing of motions and markers, multiresolution blending.
#include "signal/laplacian_pyramid.h"
#include "signal/motion_blend.h"
#include "signal/motion_pyramid.h"
#include "settings/band_settings.h"
#include "python/keyword_docs.h"
#include "python/bindings.h"
#include "settings/method_settings.h"
#include "settings/pyramid_settings.h"

namespace mocapsolve::python {
namespace {

// The declared --kernel_a and --tension (settings/pyramid_settings.h), checked as the CLI does.
PyramidOptions Options(int levels, double kernel_a, double tension) {
  PyramidOptions options;
  ThrowIfError(PyramidOptionsFromSettings(PyramidSettings{kernel_a, tension}, levels, &options));
  return options;
}

// Their defaults, from the same declaration.
const PyramidSettings kPyramidDefaults;

Array SignalToArray(const Signal& s) {
  Array out({py::ssize_t{s.rows()}, py::ssize_t{s.cols()}});
  std::copy(s.data(), s.data() + s.size(), out.mutable_data());
  return out;
}

Signal ArrayToSignal(const Array& a, const char* what) {
  if (a.ndim() != 2) throw py::value_error(std::string(what) + ": expected a (samples, channels) array");
  Signal s(a.shape(0), a.shape(1));
  std::copy(a.data(), a.data() + a.size(), s.data());
  return s;
}

// Band weights as filter/bands take them: w_0 (finest band) .. w_{N-1}, w_N (top).
std::vector<double> Weights(const std::vector<double>& weights) {
  if (weights.size() < 2) throw py::value_error("--weights: need at least 2 values (N >= 1)");
  return weights;
}

py::object FilterAny(py::object data, int levels, const std::vector<double>& weights, double kernel_a,
                     double tension) {
  const PyramidOptions options = Options(levels, kernel_a, tension);
  if (py::isinstance<Motion>(data)) {
    const Motion& motion = data.cast<const Motion&>();
    Motion filtered;
    Status status = Status::Ok();
    {
      py::gil_scoped_release release;
      status = FilterMotion(motion, options, weights, &filtered);
    }
    ThrowIfError(status);
    return py::cast(std::move(filtered));
  }
  MarkerTrajectories& markers = data.cast<MarkerTrajectories&>();
  SyncMask(&markers);
  auto filtered = std::make_shared<MarkerTrajectories>();
  Status status = Status::Ok();
  {
    py::gil_scoped_release release;
    status = FilterMarkers(markers, options, weights, filtered.get());
  }
  ThrowIfError(status);
  return py::cast(filtered);
}

}  // namespace

void BindPyramid(py::module_& m) {
  m.def("laplacian_pyramid", [](const Array& signal, int levels, double kernel_a, double tension) {
        LaplacianPyramid pyramid;
        ThrowIfError(BuildLaplacianPyramid(ArrayToSignal(signal, "signal"), Options(levels, kernel_a, tension),
                                           &pyramid));
        py::list laplacian, gaussian;
        for (const Signal& s : pyramid.laplacian) laplacian.append(SignalToArray(s));
        for (const Signal& s : pyramid.gaussian) gaussian.append(SignalToArray(s));
        return py::make_tuple(laplacian, gaussian);
      }, py::arg("signal"), py::arg("levels") = 0, py::arg("kernel_a") = kPyramidDefaults.kernel_a, py::arg("tension") = kPyramidDefaults.tension,
      "Laplacian pyramid of a (samples, channels) signal (Burt & Adelson; EXPAND by cubic\n"
      "Cardinal splines): (laplacian, gaussian), lists of arrays L_0..L_{N-1} and G_1..G_N.\n"
      "levels=0: as many as the signal allows."
      "\nkernel_a: the cubic Cardinal spline kernel's a (default 0.4); tension: the spline's tension (default 0).");

  m.def("reconstruct_signal", [](const std::vector<Array>& laplacian, const Array& top,
                                 const std::vector<double>& weights, double kernel_a, double tension) {
        LaplacianPyramid pyramid;
        pyramid.options = Options(static_cast<int>(laplacian.size()), kernel_a, tension);
        for (const Array& l : laplacian) pyramid.laplacian.push_back(ArrayToSignal(l, "laplacian"));
        pyramid.gaussian.push_back(ArrayToSignal(top, "top"));
        ThrowIfError(CheckPyramidShape(pyramid));  // ReconstructSignal trusts the sizes.
        ThrowIfError(CheckBandWeights(weights, pyramid.levels(), "weights"));
        Signal out;
        ReconstructSignal(pyramid, weights, &out);
        return SignalToArray(out);
      }, py::arg("laplacian"), py::arg("top"), py::arg("weights"), py::arg("kernel_a") = kPyramidDefaults.kernel_a,
      py::arg("tension") = kPyramidDefaults.tension,
      "Collapses a pyramid with each band scaled: w_N G_N + sum w_l L_l (Huang et al. eq. 7).\n"
      "laplacian: the arrays L_0..L_{N-1} of laplacian_pyramid(); top: G_N; weights: N + 1\n"
      "numbers w_0..w_N."
      "\nkernel_a: the cubic Cardinal spline kernel's a (default 0.4); tension: the spline's tension (default 0).");

  m.def("filter", [](py::object data, int levels, double kernel_a, double tension) {
        if (levels < 1 || levels > 30) throw py::value_error("--levels must be in [1, 30]");
        return FilterAny(data, levels, DropFinestBands(levels, levels), kernel_a, tension);
      }, py::arg("data"), py::arg("levels") = DeclaredDefault(BandSettingOptions(), "levels"),
      py::arg("kernel_a") = kPyramidDefaults.kernel_a, py::arg("tension") = kPyramidDefaults.tension,
      "Multiresolution low-pass filter of a Motion or Markers, as `mocapsolve filter`: the\n"
      "pyramid of `levels` levels collapsed without its `levels` finest bands. Returns the\n"
      "same type (missing marker samples stay missing). data: a Motion or Markers."
      "\nkernel_a: the cubic Cardinal spline kernel's a (default 0.4); tension: the spline's tension (default 0).");

  m.def("bands", [](py::object data, const std::vector<double>& weights, double kernel_a, double tension) {
        const std::vector<double> w = Weights(weights);
        return FilterAny(data, static_cast<int>(w.size()) - 1, w, kernel_a, tension);
      }, py::arg("data"), py::arg("weights"), py::arg("kernel_a") = kPyramidDefaults.kernel_a, py::arg("tension") = kPyramidDefaults.tension,
      "Band editing of a Motion or Markers, as `mocapsolve bands`: N + 1 weights (w_0 the\n"
      "finest band, w_N the top Gaussian) scale the bands of an N-level pyramid of data."
      "\nkernel_a: the cubic Cardinal spline kernel's a (default 0.4); tension: the spline's tension (default 0).");

  m.def("blend", [](const Motion& a, const Motion& b, int b_offset, int transition_start, int transition_end,
                    const std::string& method, int levels, double kernel_a, double tension) {
        if (levels < 0 || levels > 30) throw py::value_error("--blend_levels must be in [0, 30]");
        BlendOptions options;
        options.b_offset = b_offset;
        options.transition_start = transition_start;
        options.transition_end = transition_end;
        ThrowIfError(BlendMethodOption().Validate(MethodSetting{method}));
        options.method = method == "multires" ? BlendMethod::kMultiresolution : BlendMethod::kWeightedSum;
        options.pyramid = Options(levels, kernel_a, tension);
        Motion out;
        Status status = Status::Ok();
        {
          py::gil_scoped_release release;
          status = BlendMotions(a, b, options, &out);
        }
        ThrowIfError(status);
        return out;
      }, py::arg("a"), py::arg("b"), py::kw_only(), py::arg("b_offset"), py::arg("transition_start"),
      py::arg("transition_end"), py::arg("method") = DefaultMethod(BlendMethodOption()), py::arg("blend_levels") = 4,
      py::arg("kernel_a") = kPyramidDefaults.kernel_a, py::arg("tension") = kPyramidDefaults.tension,
      "Blends motion b into a over A's frames [transition_start, transition_end] (b's frame 0\n"
      "at A's frame b_offset), as `mocapsolve blend`: method 'multires' (band by band,\n"
      "blend_levels levels, 0 = as many as fit) or 'weighted' (a plain weighted sum)."
      "\nkernel_a: the cubic Cardinal spline kernel's a (default 0.4); tension: the spline's tension (default 0).");

  m.def("velocity_jumps", [](const Skeleton& skeleton, const Motion& motion) {
        CheckMotion(skeleton, motion);
        return VelocityJumps(skeleton, motion);
      }, py::arg("skeleton"), py::arg("motion"), "Per-frame joint velocity jumps of motion on skeleton (signal/motion_blend.h).");
}

}  // namespace mocapsolve::python
