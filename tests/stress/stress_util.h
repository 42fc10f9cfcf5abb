#pragma once
// Shared by the stress suite: render a scene text in-process and read pixels back.
#include <optional>

#include "render/render_job.h"
#include "test_util.h"

namespace glint::stress {

inline RenderResult renderText(const std::string& text, AccelKind kind = AccelKind::Embree,
                               std::function<void(int, int, Radiance&)> hook = nullptr) {
  const Scene s = test::sceneFromText(text);
  const auto accel = makeAccelerator(kind, s);
  RenderOptions opt;
  opt.progress = false;
  opt.sampleHook = std::move(hook);
  return renderScene(s, *accel, opt);
}

inline std::string num(double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

inline std::string vec(double x, double y, double z) {
  return "[" + num(x) + "," + num(y) + "," + num(z) + "]";
}

}  // namespace glint::stress
