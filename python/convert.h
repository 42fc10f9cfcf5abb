#pragma once
// Between Python values and Glint's: JSON (scenes in, statistics and records out) and Glint's
// errors as Python exceptions (glint.SceneError for a scene's mistakes, with file, line and path).
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>
#include <string>

#include "render/frame_record.h"

namespace glint::python {

namespace py = pybind11;

// A scene given as Python dicts, lists, strings, numbers, booleans and None, as JSON. Throws
// SceneError naming the value's path where it is not JSON (a NaN or infinity, a key that is not
// a string, another type, nesting deeper than kMaxDepth: a dict that holds itself).
nlohmann::json toJson(const py::handle& value);
inline constexpr int kMaxDepth = 256;

py::object toPython(const nlohmann::json& value);

// A path given as str, bytes or os.PathLike (pathlib.Path), as os.fsencode gives its bytes.
std::string pathOf(const py::handle& path);

// A frame record's attributes as a dict, by their EXR names (glint:spp, ...), only those it has.
py::dict recordDict(const FrameRecord& record);

// Registers glint.SceneError (a ValueError) on `module` and the translation of Glint's errors:
// SceneError → glint.SceneError, UsageError → ValueError, OutOfMemoryError → MemoryError,
// other GlintErrors → RuntimeError.
void registerErrors(py::module_& module);

}  // namespace glint::python
