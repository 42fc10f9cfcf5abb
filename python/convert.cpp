#include "convert.h"

#include <cmath>

#include "core/error.h"
#include "io/json_source.h"

namespace glint::python {

namespace {

std::string keyPath(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

[[noreturn]] void notJson(const std::string& path, const std::string& problem) {
  throw SceneError({"<dict>", 0}, path.empty() ? "(the scene)" : path, problem);
}

nlohmann::json toJsonAt(const py::handle& v, const std::string& path, int depth) {
  if (depth > kMaxDepth)
    notJson(path, "nested deeper than " + std::to_string(kMaxDepth) +
                      " levels (a dict or list that holds itself?)");
  if (v.is_none()) return nullptr;
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>();
  if (py::isinstance<py::int_>(v)) {
    int overflow = 0;
    const long long n = PyLong_AsLongLongAndOverflow(v.ptr(), &overflow);
    if (overflow != 0)
      notJson(path, "the integer " + excerpt(py::str(v)) + " does not fit 64 bits");
    return int64_t(n);
  }
  if (py::isinstance<py::float_>(v)) {
    const double d = v.cast<double>();
    if (!std::isfinite(d)) notJson(path, "must be a finite number, got " + formatNumber(d));
    return d;
  }
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::dict>(v)) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& [key, value] : v.cast<py::dict>()) {
      if (!py::isinstance<py::str>(key))
        notJson(path, "keys must be strings, got " + excerpt(py::repr(key)));
      const std::string k = key.cast<std::string>();
      out[k] = toJsonAt(value, keyPath(path, k), depth + 1);
    }
    return out;
  }
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    nlohmann::json out = nlohmann::json::array();
    size_t i = 0;
    for (const auto& item : v)
      out.push_back(toJsonAt(item, path + "[" + std::to_string(i++) + "]", depth + 1));
    return out;
  }
  // NumPy arrays (an eye or a colour from a notebook): as the nested lists they hold.
  if (py::hasattr(v, "tolist") && py::hasattr(v, "ndim") && v.attr("ndim").cast<int>() > 0)
    return toJsonAt(v.attr("tolist")(), path, depth + 1);
  // NumPy scalars and other numbers: by their float value.
  if (py::hasattr(v, "__float__") && !py::isinstance<py::bytes>(v)) {
    const double d = v.attr("__float__")().cast<double>();
    if (!std::isfinite(d)) notJson(path, "must be a finite number, got " + formatNumber(d));
    return d;
  }
  notJson(path, "a scene holds dicts, lists, strings, numbers, booleans and None, got " +
                    std::string(py::str(v.get_type().attr("__name__"))));
}

}  // namespace

nlohmann::json toJson(const py::handle& value) {
  if (!py::isinstance<py::dict>(value))
    throw py::type_error("a scene is a dict (the JSON scene format), got " +
                         std::string(py::str(value.get_type().attr("__name__"))));
  return toJsonAt(value, "", 0);
}

py::object toPython(const nlohmann::json& v) {
  switch (v.type()) {
    case nlohmann::json::value_t::null:
      return py::none();
    case nlohmann::json::value_t::boolean:
      return py::bool_(v.get<bool>());
    case nlohmann::json::value_t::number_integer:
      return py::int_(v.get<int64_t>());
    case nlohmann::json::value_t::number_unsigned:
      return py::int_(v.get<uint64_t>());
    case nlohmann::json::value_t::number_float:
      return py::float_(v.get<double>());
    case nlohmann::json::value_t::string:
      return py::str(v.get<std::string>());
    case nlohmann::json::value_t::array: {
      py::list out;
      for (const auto& item : v) out.append(toPython(item));
      return out;
    }
    case nlohmann::json::value_t::object: {
      py::dict out;
      for (const auto& [key, item] : v.items()) out[py::str(key)] = toPython(item);
      return out;
    }
    default:
      return py::none();
  }
}

std::string pathOf(const py::handle& path) {
  // The file system's bytes, as open(2) takes them: str(b"x.exr") named "b'x.exr'", and a str
  // with the surrogates of a name that is not UTF-8 could not be encoded at all.
  const py::bytes bytes = py::module_::import("os").attr("fsencode")(path);
  return std::string(bytes);
}

py::dict recordDict(const FrameRecord& r) {
  py::dict d;
  const auto put = [&](const char* key, const auto& value) {
    if (value) d[key] = *value;
  };
  put("glint:version", r.version);
  put("glint:scene", r.scene);
  put("glint:scene_hash", r.sceneHash);
  put("glint:settings_hash", r.settingsHash);
  put("glint:integrator", r.integrator);
  if (r.sampler) d["glint:sampler"] = std::string(samplerName(*r.sampler));
  if (r.passes) d["glint:passes"] = toPython(nlohmann::json::parse(passesJson(*r.passes)));
  put("glint:accel", r.accel);
  put("glint:seed", r.seed);
  if (r.crop) d["glint:crop"] = py::make_tuple(r.crop->x0, r.crop->x1, r.crop->y0, r.crop->y1);
  put("glint:commandline", r.commandLine);
  put("glint:colorspace", r.colorspace);
  put("glint:spp", r.spp);
  put("glint:max_spp", r.maxSpp);
  put("glint:time_limit_seconds", r.timeLimitSeconds);
  put("glint:resume_sampling", r.resumeSampling);
  put("glint:max_depth", r.maxDepth);
  put("glint:partial", r.partial);
  put("glint:min_pixel_spp", r.minPixelSpp);
  put("glint:max_pixel_spp", r.maxPixelSpp);
  put("glint:frame", r.frame);
  put("glint:render_seconds", r.renderSeconds);
  put("glint:rays", r.rays);
  put("glint:estimated_rmse", r.estimatedRmse);
  put("glint:estimated_relmse", r.estimatedRelmse);
  put("glint:clamped_values", r.clampedValues);
  put("glint:merged_crops", r.mergedCrops);
  put("pixelAspectRatio", r.pixelAspectRatio);
  d["display_window"] = py::make_tuple(r.frameWidth, r.frameHeight);
  return d;
}

namespace {

// A message as Python text: a path holding bytes that are not UTF-8 (os.fsencode of a Latin-1
// name) kept as surrogates, as os.fsdecode gives them, where py::str raised UnicodeDecodeError
// in place of the error and PyErr_SetString an empty one.
py::str text(const std::string& message) {
  return py::reinterpret_steal<py::str>(
      PyUnicode_DecodeUTF8(message.data(), py::ssize_t(message.size()), "surrogateescape"));
}

}  // namespace

void registerErrors(py::module_& module) {
  static py::exception<SceneError> sceneError(module, "SceneError", PyExc_ValueError);
  sceneError.doc() =
      "A mistake in a scene: str() is 'file:line: path: problem'; the attributes file, line "
      "(0 where unknown), path (the JSON path) and problem hold its parts.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const SceneError& e) {
      py::object error = py::reinterpret_borrow<py::object>(sceneError)(text(e.what()));
      error.attr("file") = text(e.loc().file);
      error.attr("line") = e.loc().line;
      error.attr("path") = text(e.path());
      error.attr("problem") = text(e.problem());
      PyErr_SetObject(sceneError.ptr(), error.ptr());
    } catch (const UsageError& e) {
      PyErr_SetObject(PyExc_ValueError, text(e.what()).ptr());
    } catch (const OutOfMemoryError& e) {
      PyErr_SetObject(PyExc_MemoryError, text(e.what()).ptr());
    } catch (const GlintError& e) {
      PyErr_SetObject(PyExc_RuntimeError, text(e.what()).ptr());
    }
  });
}

}  // namespace glint::python
