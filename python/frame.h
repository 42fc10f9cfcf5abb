#pragma once
// glint.Frame: a rendered frame (Scene.render) or one read from an EXR (glint.read_frame). Its
// pixels are one float32 buffer, H × W × C interleaved, whose NumPy views (.rgba, each AOV,
// .channel(name)) share it without a copy; a rendered frame keeps what its EXR is written from,
// so that .write(path) writes the file `glint render` writes.
#include <pybind11/pybind11.h>

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "render/frame_record.h"
#include "render/pass_plan.h"
#include "render/render_job.h"
#include "scene/scene.h"

namespace glint::python {

namespace py = pybind11;

// What a render leaves for .write and .record.
struct Rendered {
  std::shared_ptr<const Scene> scene;
  FrameSettings settings;
  PassPlan plan;
  RenderResult result;
  int threads = 0;
};

struct Layer {
  std::string name;
  int first = 0, count = 0;  // its channels in the frame's buffer
};

class Frame {
 public:
  // A render's frame: RGBA, then each AOV plane's channels, rounded to float as the EXR holds
  // them (values beyond float's range clamped to it, counted in stats' clamped_values).
  explicit Frame(Rendered rendered);
  // An EXR read back: every channel in readImage's order, the layers by their EXR names. Called
  // with the GIL, which it releases while it reads.
  explicit Frame(const std::string& path);

  int width() const { return width_; }
  int height() const { return height_; }
  int channelCount() const { return int(channels_.size()); }
  const std::vector<std::string>& channels() const { return channels_; }
  const std::vector<Layer>& layers() const { return layers_; }
  float* data() { return pixels_.data(); }
  bool partial() const { return partial_; }
  std::pair<int, int> origin() const { return {x0_, y0_}; }
  std::pair<int, int> fullSize() const { return {fullWidth_, fullHeight_}; }
  const py::object& stats() const { return stats_; }
  py::dict record() const;
  int channelIndex(const std::string& name) const;  // throws KeyError
  bool hasRgba() const { return rgba_; }
  void write(const std::string& path, bool half, const std::string& compression,
             bool multipart) const;

 private:
  int width_ = 0, height_ = 0, x0_ = 0, y0_ = 0, fullWidth_ = 0, fullHeight_ = 0;
  std::vector<std::string> channels_;
  std::vector<Layer> layers_;
  std::vector<float> pixels_;
  bool rgba_ = false, partial_ = false;
  py::object stats_ = py::none();
  std::optional<Rendered> rendered_;
  std::optional<FrameRecord> record_;  // a read frame's
};

void bindFrame(py::module_& module);

}  // namespace glint::python
