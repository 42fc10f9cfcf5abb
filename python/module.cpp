// The `glint` Python module (docs/python.md): scenes in, NumPy frames and figures out, through
// the same libraries and the same render session as the `glint` command.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <tuple>

#include <glint_version.h>

#include "app/scene_validation.h"
#include "convert.h"
#include "core/error.h"
#include "core/input_files.h"
#include "film/compare.h"
#include "film/rgb_channels.h"
#include "frame.h"
#include "render.h"

namespace glint::python {

const Scene& sceneOf(const py::object& scene);  // render.cpp

namespace {

py::object errorsDict(const ImageErrors& e) {
  const auto finite = [](double v) {
    return std::isfinite(v) ? py::object(py::float_(v)) : py::object(py::none());
  };
  py::dict d;
  d["rmse"] = finite(e.rmse);
  d["relmse"] = finite(e.relmse);
  d["mae"] = finite(e.mae);
  d["max_abs"] = finite(e.maxAbs);
  d["psnr"] = finite(e.psnr);
  d["share_above_threshold"] = e.aboveThreshold;
  d["pixels"] = e.pixels;
  d["nonfinite_pixels"] = e.nonfinitePixels;
  return d;
}

// An image to compare: a path (an EXR, as `glint compare` reads it), a Frame, or an array of
// H x W x C (C ≥ 3: RGB first) or H x W (one channel, taken as grey).
Image imageOf(const py::object& v, const char* which) {
  if (py::isinstance<py::str>(v) || py::isinstance<py::bytes>(v) || py::hasattr(v, "__fspath__")) {
    const std::string path = pathOf(v);
    py::gil_scoped_release unlocked;
    const InputReadAlone alone(path);
    Image img = readImage(path);
    requireRgb(img, path, "compare");
    return img;
  }
  if (v.is_none())
    throw py::type_error(std::string(which) + " must be a path, a Frame or an array, not None");
  py::object source = v;
  const Frame* frame = py::isinstance<Frame>(v) ? &v.cast<const Frame&>() : nullptr;
  if (frame) source = v.attr("rgba");
  const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(source);
  if (!a) throw py::type_error(std::string(which) + " must be a path, a Frame or an array");
  if (a.ndim() != 2 && a.ndim() != 3)
    throw py::value_error(std::string(which) + " must be H x W or H x W x C, got " +
                          std::to_string(a.ndim()) + " dimensions");
  const ssize_t h = a.shape(0), w = a.shape(1), c = a.ndim() == 3 ? a.shape(2) : 1;
  if (h < 1 || w < 1 || (c != 1 && c < 3))
    throw py::value_error(std::string(which) +
                          " must have 1, 3 or more channels (RGB first) "
                          "and at least one pixel");
  Image img;
  img.width = int(w);
  img.height = int(h);
  // A frame's pixels keep their place in its frame; an array's place is unknown (0 x 0), so
  // compare sets it beside any.
  if (frame) {
    std::tie(img.x, img.y) = frame->origin();
    std::tie(img.fullWidth, img.fullHeight) = frame->fullSize();
  }
  img.channels = 4;
  img.pixels.resize(size_t(h * w * 4));
  const float* p = a.data();
  for (ssize_t i = 0; i < h * w; ++i)
    for (int k = 0; k < 4; ++k)
      img.pixels[size_t(i * 4 + k)] = k == 3 ? 1.0f : p[i * c + (c == 1 ? 0 : k)];
  return img;
}

// What compare's errors call an argument: its path, or the argument and what it is.
std::string nameOf(const py::object& v, const char* which) {
  if (py::isinstance<py::str>(v) || py::isinstance<py::bytes>(v) || py::hasattr(v, "__fspath__"))
    return pathOf(v);
  return std::string(which) + (py::isinstance<Frame>(v) ? " (a Frame)" : " (an array)");
}

}  // namespace

}  // namespace glint::python

PYBIND11_MODULE(_glint, m) {
  namespace py = pybind11;
  using namespace glint;
  using namespace glint::python;
  m.doc() = "Glint, a production-style ray tracer: scenes in, NumPy frames and figures out";
  m.attr("__version__") = GLINT_VERSION;
  registerErrors(m);
  bindFrame(m);
  bindScene(m);
  m.def(
      "read_frame",
      [](const py::object& path) {
        return std::make_shared<Frame>(pathOf(path));  // reads the file without the GIL
      },
      py::arg("path"),
      "An EXR frame: every channel as NumPy views (.rgba, .aovs by AOV name, .channel(name)) and "
      "its record (.record: the glint:* attributes)");
  m.def(
      "compare",
      [](const py::object& a, const py::object& b, double threshold) {
        if (!(threshold > 0) || !std::isfinite(threshold))
          throw py::value_error("threshold must be a finite number above 0");
        const Image test = imageOf(a, "a"), reference = imageOf(b, "b");
        const ComparedNames names{nameOf(a, "a"), nameOf(b, "b")};
        py::gil_scoped_release unlocked;
        const ImageErrors e = compareImages(test, reference, threshold, names);
        py::gil_scoped_acquire locked;
        for (const std::string& note :
             {e.placement, e.nonfinitePixels > 0 ? nonfiniteNote(e, names) : std::string()})
          if (!note.empty() && PyErr_WarnEx(PyExc_UserWarning, note.c_str(), 1) != 0)
            throw py::error_already_set();
        return errorsDict(e);
      },
      py::arg("a"), py::arg("b"), py::arg("threshold") = 1e-2,
      "Error metrics of a against the reference b, as `glint compare --json` gives them (rmse, "
      "relmse, mae, max_abs, psnr, ...): each a path, a Frame or an array (RGB)");
  m.def(
      "validate",
      [](const py::object& scene, int64_t rays, int64_t seed, int64_t spp, bool brute) {
        if (rays < 0 || rays > (1 << 30)) throw py::value_error("rays must be from 0 to 2^30");
        if (seed < 0) throw py::value_error("seed must be 0 or more");
        if (spp < 0 || spp > (1 << 16)) throw py::value_error("spp must be from 0 to 65536");
        const Scene& s = sceneOf(scene);
        ValidateSettings settings;
        settings.rays = int(rays);
        settings.seed = uint64_t(seed);
        settings.spp = int(spp);
        settings.noBrute = !brute;
        checkSomethingIsCast(settings);
        nlohmann::json figures;
        {
          py::gil_scoped_release unlocked;
          const ValidationBackends backends(s, settings);
          Scene rendered = s;  // validateScene sets its spp; the Python scene stays as it was
          figures = validateScene(rendered, backends, settings, false);
        }
        return toPython(figures);
      },
      py::arg("scene"), py::kw_only(), py::arg("rays") = 100000, py::arg("seed") = 1,
      py::arg("spp") = 1, py::arg("brute") = true,
      "Cross-checks Embree against every other backend on the scene's own rays and `rays` "
      "random ones, as `glint validate` does: its --json figures as a dict");
}
