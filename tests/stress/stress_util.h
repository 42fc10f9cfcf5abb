#pragma once
// Shared by the stress suite: render a scene text in-process and read pixels back. Every
// stress scene is also rendered by the reference integrator, the production kernel's oracle,
// which must give the same image (oracle_util.h).
#include <optional>

#include "oracle_util.h"
#include "render/render_job.h"
#include "test_util.h"

namespace glint::stress {

inline RenderResult renderText(const std::string& text, AccelKind kind = AccelKind::Embree,
                               std::function<void(int, int, Radiance&)> hook = nullptr) {
  const Scene s = test::sceneFromText(text);
  const auto accel = makeAccelerator(kind, s);
  RenderOptions opt;
  opt.progress = false;
  RenderResult production = [&] {
    RenderOptions withHook = opt;
    withHook.sampleHook = hook;
    return renderScene(s, *accel, withHook);
  }();
  // A hook alters samples on their way to the film (a forced NaN): not the optics.
  if (!hook) test::expectReferenceAgrees(s, *accel, opt, production.film, "stress scene");
  return production;
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
