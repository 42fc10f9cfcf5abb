#include "frame.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cfloat>
#include <set>

#include "app/frame_output.h"
#include "convert.h"
#include "core/error.h"
#include "core/input_files.h"
#include "core/word_list.h"
#include "film/atomic_file.h"
#include "film/display.h"
#include "film/exr_output.h"
#include "film/image_format.h"
#include "integrator/aov.h"
#include "render/tile_scheduler.h"

namespace glint::python {

namespace {

// As writeExr rounds a film value to a float channel: clamped to float's finite range.
float toChannel(double v, uint64_t& clamped) {
  if (v > double(FLT_MAX) || v < -double(FLT_MAX)) {
    ++clamped;
    return v > 0 ? FLT_MAX : -FLT_MAX;
  }
  return float(v);
}

// The layer a channel of an EXR belongs to: the name before its last dot ("N" of "N.X"), or
// the channel itself ("Z").
std::string layerOf(const std::string& channel) {
  const size_t dot = channel.rfind('.');
  return dot == std::string::npos ? channel : channel.substr(0, dot);
}

}  // namespace

Frame::Frame(Rendered r) {
  const Film& film = r.result.film;
  const PixelWindow& w = film.window();
  width_ = w.width();
  height_ = w.height();
  x0_ = w.x0;
  y0_ = w.y0;
  fullWidth_ = film.fullWidth();
  fullHeight_ = film.fullHeight();
  partial_ = r.result.partial;
  channels_ = {"R", "G", "B", "A"};
  layers_.push_back({"rgba", 0, 4});
  for (const FilmPlane& p : film.planes()) {
    layers_.push_back({p.name, int(channels_.size()), int(p.channels.size())});
    channels_.insert(channels_.end(), p.channels.begin(), p.channels.end());
  }
  rgba_ = true;
  const size_t c = channels_.size(), pixels = size_t(w.area());
  pixels_.resize(pixels * c);
  uint64_t clamped = 0;
  for (int y = w.y0; y < w.y1; ++y)
    for (int x = w.x0; x < w.x1; ++x) {
      float* out = &pixels_[(size_t(y - w.y0) * size_t(width_) + size_t(x - w.x0)) * c];
      const float* rgba = film.pixel(x, y);
      for (int k = 0; k < 4; ++k) *out++ = toChannel(rgba[k], clamped);
      for (size_t p = 0; p < film.planes().size(); ++p) {
        const double* v = film.planePixel(p, x, y);
        for (size_t k = 0; k < film.planes()[p].channels.size(); ++k)
          *out++ = toChannel(v[k], clamped);
      }
    }
  stats_ = toPython(renderStatsJson(*r.scene, r.result.stats, clamped));
  rendered_ = std::move(r);
}

Frame::Frame(const std::string& path) {
  Image img;
  {
    // Only the file's reading goes without the GIL: the members hold Python objects.
    py::gil_scoped_release unlocked;
    const InputReadAlone alone(path);
    img = readImage(path, ExrParts::All);  // a --multipart frame's AOVs too
    record_ = readFrameRecord(path);
  }
  for (const std::string& part : img.partsLeftOut)
    if (PyErr_WarnEx(PyExc_UserWarning, (path + ": " + part + "; it is left out").c_str(), 1) != 0)
      throw py::error_already_set();  // warnings turned into errors
  width_ = img.width;
  height_ = img.height;
  x0_ = img.x;
  y0_ = img.y;
  fullWidth_ = img.fullWidth;
  fullHeight_ = img.fullHeight;
  channels_ = img.channelNames;
  pixels_ = std::move(img.pixels);
  partial_ = record_->partial.value_or(false);
  rgba_ = channels_.size() >= 4 && channels_[0] == "R" && channels_[1] == "G" &&
          channels_[2] == "B" && channels_[3] == "A";
  size_t k = rgba_ ? 4 : 0;
  if (rgba_) layers_.push_back({"rgba", 0, 4});
  while (k < channels_.size()) {
    const std::string layer = layerOf(channels_[k]);
    size_t end = k + 1;
    while (end < channels_.size() && layerOf(channels_[end]) == layer) ++end;
    layers_.push_back({layer, int(k), int(end - k)});
    k = end;
  }
  // Named as the render names it where its channels are an AOV's (Z: depth, N: normal), unless
  // another layer of the file has that name already (another tool's "depth").
  std::set<std::string> names;
  for (const Layer& l : layers_) names.insert(l.name);
  for (Layer& l : layers_) {
    const AovPlane* aov =
        aovPlaneWithChannels({channels_.begin() + l.first, channels_.begin() + l.first + l.count});
    if (aov && names.insert(aov->name).second) l.name = aov->name;
  }
}

py::dict Frame::record() const {
  if (record_) return recordDict(*record_);
  const Rendered& r = *rendered_;
  return recordDict(frameRecord(*r.scene, r.settings, r.plan, r.result, r.result.partial));
}

int Frame::channelIndex(const std::string& name) const {
  const auto it = std::find(channels_.begin(), channels_.end(), name);
  if (it == channels_.end()) {
    std::string names;
    for (const std::string& c : channels_) names += (names.empty() ? "" : ", ") + c;
    throw py::key_error("no channel " + inQuotes(name) + "; the frame has " + names);
  }
  return int(it - channels_.begin());
}

void Frame::write(const std::string& path, bool half, const std::string& compression,
                  bool multipart) const {
  if (!rendered_) throw py::value_error("a frame read from a file is written by copying the file");
  const ImageFormat format = imageOutputFormat("path", path, ImageOutput::ExrOrDisplay);
  checkOutputPaths({{"path", path}});
  const Rendered& r = *rendered_;
  if (std::find(exrCompressions().begin(), exrCompressions().end(), compression) ==
      exrCompressions().end())
    throw py::value_error("compression " + inQuotes(compression) + " is not one OpenEXR writes");
  if (isDisplayFormat(format)) {
    // What only the EXR frame carries, refused as the command refuses it (it was dropped
    // without a word).
    std::vector<std::string> exrOnly;
    if (half) exrOnly.push_back("half=True");
    if (multipart) exrOnly.push_back("multipart=True");
    if (compression != "zip") exrOnly.push_back("compression=" + inQuotes(compression));
    if (!r.result.film.planes().empty()) exrOnly.push_back("the frame's AOVs");
    if (!exrOnly.empty())
      throw py::value_error(path + " is a display image, which cannot carry " + wordList(exrOnly) +
                            " (only an .exr can): write the frame to an .exr too");
  }
  py::gil_scoped_release unlocked;
  if (isDisplayFormat(format)) {
    if (r.result.partial)
      throw UsageError(path + ": a display image cannot mark a frame partial; write an .exr");
    writeDisplayImage(path, r.result.film, DisplaySettings{},
                      r.scene->render.transparentBackground);
    return;
  }
  setExrThreads(std::min(threadCount(r.threads), defaultThreadCount()));
  writeFrameExr(path, *r.scene, r.settings, r.plan, r.result, r.result.partial,
                {half, compression, multipart});
}

namespace {

// A view of channels [first, first + count) of the frame's buffer, sharing it (`owner` keeps
// the frame alive as the array's base); read-only, since .write writes the render's own film.
py::array view(Frame& f, const py::object& owner, int first, int count, bool squeeze) {
  const ssize_t c = f.channelCount();
  std::vector<ssize_t> shape{f.height(), f.width()};
  std::vector<ssize_t> strides{ssize_t(sizeof(float)) * c * f.width(), ssize_t(sizeof(float)) * c};
  if (!squeeze) {
    shape.push_back(count);
    strides.push_back(sizeof(float));
  }
  py::array a(py::dtype::of<float>(), shape, strides, f.data() + first, owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

}  // namespace

void bindFrame(py::module_& m) {
  py::class_<Frame, std::shared_ptr<Frame>>(
      m, "Frame",
      "A frame: pixels as NumPy float32 arrays (H x W x C views of one buffer, no copy), the "
      "render's statistics, its record, and write(path) for the EXR `glint render` writes.")
      .def_property_readonly("width", &Frame::width)
      .def_property_readonly("height", &Frame::height)
      .def_property_readonly("origin", &Frame::origin,
                             "(x0, y0): the crop's corner in the full frame, (0, 0) for a frame")
      .def_property_readonly("full_size", &Frame::fullSize, "(width, height) of the full frame")
      .def_property_readonly("partial", &Frame::partial,
                             "True when an interrupt or a cancel cut the frame short: each pixel "
                             "keeps the passes it finished (alpha 0 where none)")
      .def_property_readonly("channels", &Frame::channels, "every channel's name, in order")
      .def_property_readonly(
          "rgba",
          [](py::object self) {
            Frame& f = self.cast<Frame&>();
            if (!f.hasRgba()) throw py::attribute_error("the frame has no R, G, B, A channels");
            return view(f, self, 0, 4, false);
          },
          "H x W x 4 float32: scene-linear RGB and alpha (coverage)")
      .def_property_readonly(
          "aovs",
          [](py::object self) {
            Frame& f = self.cast<Frame&>();
            py::dict d;
            // The resume state (glint_resume.*) is Glint's bits, not an image: channel() reads it.
            for (const Layer& l : f.layers())
              if (l.name != "rgba" && l.name != "glint_resume")
                d[py::str(l.name)] = view(f, self, l.first, l.count, false);
            return d;
          },
          "{name: H x W x C float32}: the AOVs by their names (depth, normal, ...), in a frame "
          "read from a file too; its other layers by their EXR names")
      .def(
          "channel",
          [](py::object self, const std::string& name) {
            Frame& f = self.cast<Frame&>();
            return view(f, self, f.channelIndex(name), 1, true);
          },
          py::arg("name"), "H x W float32: one channel by its EXR name (\"N.X\", \"Z\", \"A\")")
      .def_property_readonly("stats", &Frame::stats,
                             "a render's statistics: the dictionary `--stats-json` writes; None "
                             "for a frame read from a file")
      .def_property_readonly("record", &Frame::record,
                             "the frame's record (docs/output.md): the EXR attributes by name")
      .def(
          "write",
          [](const Frame& f, const py::object& path, bool half, const std::string& compression,
             bool multipart) { f.write(pathOf(path), half, compression, multipart); },
          py::arg("path"), py::arg("half") = false, py::arg("compression") = "zip",
          py::arg("multipart") = false,
          "Writes the frame: .exr as `glint render -o` writes it (metadata, a partial frame "
          "marked partial with its resume state), .png/.jpg/.tif through the OCIO view")
      .def("__repr__", [](const Frame& f) {
        return "<glint.Frame " + std::to_string(f.width()) + "x" + std::to_string(f.height()) +
               ", " + std::to_string(f.channelCount()) + " channels" +
               (f.partial() ? ", partial>" : ">");
      });
}

}  // namespace glint::python
