#pragma once
// glint.Scene and Scene.render: a scene loaded once, rendered by the render session `glint
// render` drives (render/render_session.h), on a thread of its own while the calling thread
// waits without the GIL, takes progress to the callback and Ctrl-C to the render.
#include <pybind11/pybind11.h>

namespace glint::python {

namespace py = pybind11;

void bindScene(py::module_& module);

}  // namespace glint::python
