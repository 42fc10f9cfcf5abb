#include "render.h"

#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <filesystem>
#include <mutex>
#include <thread>

#include "app/scene_source.h"
#include "convert.h"
#include "core/error.h"
#include "frame.h"
#include "io/json_source.h"
#include "io/scene_loader.h"
#include "render/render_session.h"
#include "render/tile_scheduler.h"

namespace glint::python {

namespace {

// How often the waiting thread looks for a signal (Ctrl-C) and progress to report: well under
// the render's own latency, the chunk of camera samples in flight when the cancel flag is set.
constexpr auto kPollInterval = std::chrono::milliseconds(20);

struct PyScene {
  std::shared_ptr<const Scene> scene;
};

// A seed as --seed takes it, 0 to 2^64 - 1 (pybind11's int64_t refused seeds the command line
// writes into frames, past 2^63, with an opaque TypeError); None where not given.
std::optional<uint64_t> seedOf(const py::object& seed) {
  if (seed.is_none()) return std::nullopt;
  if (!py::isinstance<py::int_>(seed) || py::isinstance<py::bool_>(seed))
    throw py::type_error("seed must be an int, got " +
                         std::string(py::str(py::type::of(seed).attr("__name__"))));
  const unsigned long long value = PyLong_AsUnsignedLongLong(seed.ptr());
  if (value == static_cast<unsigned long long>(-1) && PyErr_Occurred()) {
    PyErr_Clear();
    throw py::value_error("seed must be from 0 to 2^64 - 1, got " + std::string(py::str(seed)));
  }
  return uint64_t{value};
}

// The keyword arguments of Scene.render, checked as `glint render` checks its options.
struct RenderRequest {
  std::optional<int64_t> spp;
  std::optional<uint64_t> seed;  // 64 bits, as --seed takes
  std::optional<int64_t> threads, width, height, maxDepth, minSpp, maxSpp;
  std::optional<std::vector<int64_t>> crop;
  std::vector<std::string> aovs;
  std::optional<std::string> sampler;
  std::optional<double> targetRmse, targetRelmse, timeLimit;
  std::string accel = "embree", integrator = "production";
  bool resumable = false;
};

int checkedInt(const char* name, const std::optional<int64_t>& v, int64_t lo, int64_t hi) {
  if (*v < lo || *v > hi)
    throw py::value_error(std::string(name) + " must be from " + std::to_string(lo) + " to " +
                          std::to_string(hi) + ", got " + std::to_string(*v));
  return int(*v);
}

double positive(const char* name, double v) {
  if (!(v > 0) || !std::isfinite(v))
    throw py::value_error(std::string(name) + " must be a finite number above 0, got " +
                          formatNumber(v));
  return v;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const std::string& n : names) s += (s.empty() ? "" : ",") + n;
  return s;
}

// The progress callback's view of a finished pass.
py::dict passDict(const PassRecord& p, size_t index, size_t planned) {
  py::dict d;
  d["pass"] = index;
  d["passes_planned"] = planned;
  d["spp"] = p.spp;
  d["mean_spp"] = p.meanSpp;
  d["seconds"] = p.seconds;
  d["estimated_rmse"] = p.estimated.rmse ? py::object(py::float_(*p.estimated.rmse)) : py::none();
  d["estimated_relmse"] =
      p.estimated.relmse ? py::object(py::float_(*p.estimated.relmse)) : py::none();
  d["pixels_sampled"] = p.pixelsSampled;
  return d;
}

// The render session on its own thread, and what the waiting thread hears from it.
class RenderThread {
 public:
  // With `lockstep`, each pass waits until the caller has heard of the one before
  // (acknowledge): a progress callback that cancels after pass k always gets k passes.
  RenderThread(const Scene& scene, const Accelerator& accel, const RenderOptions& opt,
               bool lockstep)
      : lockstep_(lockstep), thread_([&scene, &accel, opt, this] { run(scene, accel, opt); }) {}
  ~RenderThread() {
    stop();
    if (thread_.joinable()) thread_.join();
  }

  void stop() {
    std::lock_guard<std::mutex> lock(mutex_);
    cancel_.store(true);
    changed_.notify_all();
  }
  // The caller has heard of `passes` passes: the next may start.
  void acknowledge(size_t passes) {
    std::lock_guard<std::mutex> lock(mutex_);
    acknowledged_ = passes;
    changed_.notify_all();
  }
  // Waits up to kPollInterval for news; returns whether the render is over, and the passes
  // finished since the last call in `fresh`.
  bool wait(std::vector<PassRecord>& fresh) {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait_for(lock, kPollInterval, [&] { return done_ || !news_.empty(); });
    fresh.swap(news_);
    news_.clear();
    return done_;
  }
  RenderResult take() {
    thread_.join();
    if (error_) std::rethrow_exception(error_);
    return std::move(*result_);
  }

 private:
  void run(const Scene& scene, const Accelerator& accel, RenderOptions opt) {
    try {
      opt.cancel = &cancel_;
      RenderSession session(scene, accel, opt);
      for (size_t passes = 1; session.runPass(); ++passes) {
        std::unique_lock<std::mutex> lock(mutex_);
        news_.push_back(session.passesFinished().back());
        changed_.notify_all();
        if (lockstep_) changed_.wait(lock, [&] { return acknowledged_ >= passes || cancel_; });
      }
      result_.emplace(session.finish());
    } catch (...) {
      error_ = std::current_exception();
    }
    std::lock_guard<std::mutex> lock(mutex_);
    done_ = true;
    changed_.notify_all();
  }

  const bool lockstep_;
  std::atomic<bool> cancel_{false};
  std::mutex mutex_;
  std::condition_variable changed_;
  std::vector<PassRecord> news_;
  bool done_ = false;
  size_t acknowledged_ = 0;
  std::optional<RenderResult> result_;
  std::exception_ptr error_;
  std::thread thread_;  // last: started once the rest exists
};

std::shared_ptr<Frame> render(const PyScene& source, const RenderRequest& q,
                              const py::object& progress) {
  auto scene = std::make_shared<Scene>(*source.scene);
  RenderSettings& rs = scene->render;
  if (q.spp) rs.spp = checkedInt("spp", q.spp, 1, kMaxSampleSet);
  if (q.width) rs.width = checkedInt("width", q.width, 1, 1 << 15);
  if (q.height) rs.height = checkedInt("height", q.height, 1, 1 << 15);
  if (q.maxDepth) rs.maxDepth = checkedInt("max_depth", q.maxDepth, 0, 1000);
  if (q.seed) rs.seed = *q.seed;
  if (q.sampler && !parseSamplerKind(*q.sampler, rs.sampler))
    throw py::value_error("sampler must be regular, random, stratified or sobol, got " +
                          inQuotes(*q.sampler));
  SamplingRequest sampling;
  if (q.targetRmse) sampling.target.rmse = positive("target_rmse", *q.targetRmse);
  if (q.targetRelmse) sampling.target.relmse = positive("target_relmse", *q.targetRelmse);
  if (q.timeLimit) sampling.timeLimitSeconds = positive("time_limit", *q.timeLimit);
  if (q.minSpp) sampling.minSpp = checkedInt("min_spp", q.minSpp, 1, kMaxSampleSet);
  if (q.maxSpp) sampling.maxSpp = checkedInt("max_spp", q.maxSpp, 1, kMaxSampleSet);
  sampling.progressive = q.resumable;
  RenderOptions opt;
  if (q.threads) opt.threads = checkedInt("threads", q.threads, 1, 4096);
  opt.progress = false;
  opt.tileCpuTimes = true;  // the statistics' schedule, as --stats-json has it
  if (!parseIntegratorKind(q.integrator, opt.integrator))
    throw py::value_error("integrator must be production or reference, got " +
                          inQuotes(q.integrator));
  AccelKind kind = AccelKind::Embree;
  if (!parseAccelKind(q.accel, kind))
    throw py::value_error("accel " + inQuotes(q.accel) + " is not a backend Glint has");
  const std::string aovs = joined(q.aovs);
  opt.aovs = AovSet::parse(aovs);
  if (sampling.progressive && opt.aovs.needsSamples())
    throw py::value_error("resumable keeps the beauty and its variance only: drop the AOVs " +
                          aovs);
  opt.sampling = sampling;
  if (q.crop) {
    const std::vector<int64_t>& c = *q.crop;
    if (c.size() != 4)
      throw py::value_error("crop is (x0, x1, y0, y1), got " + std::to_string(c.size()) +
                            " numbers");
    if (c[0] < 0 || c[1] > rs.width || c[0] >= c[1] || c[2] < 0 || c[3] > rs.height || c[2] >= c[3])
      throw py::value_error("crop [" + std::to_string(c[0]) + "," + std::to_string(c[1]) + ") x [" +
                            std::to_string(c[2]) + "," + std::to_string(c[3]) +
                            ") must be non-empty and inside the " + std::to_string(rs.width) + "x" +
                            std::to_string(rs.height) + " frame");
    opt.crop = PixelWindow{int(c[0]), int(c[1]), int(c[2]), int(c[3])};
  }
  if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
    throw py::type_error("progress must be a callable (or None)");
  // The plan the session makes, for the record; it refuses contradictory bounds here.
  const PassPlan plan = PassPlan::make(rs.spp, rs.sampler, sampling);
  const FrameSettings settings{q.accel, q.integrator, aovs,
                               false,   sampling,     "python: glint.Scene.render"};

  std::unique_ptr<Accelerator> accel;
  {
    py::gil_scoped_release unlocked;
    accel = makeAccelerator(kind, *scene, {});
  }
  py::object stopped;  // the exception that stopped the render: KeyboardInterrupt, the callback's
  std::optional<RenderResult> result;
  {
    RenderThread thread(*scene, *accel, opt, !progress.is_none());
    std::vector<PassRecord> fresh;
    size_t reported = 0;
    for (bool done = false; !done;) {
      {
        py::gil_scoped_release unlocked;
        done = thread.wait(fresh);
      }
      for (const PassRecord& p : fresh) {
        if (progress.is_none() || stopped) break;
        try {
          const py::object answer = progress(passDict(p, reported++, plan.ends.size()));
          const int truth = answer.is_none() ? 1 : PyObject_IsTrue(answer.ptr());
          if (truth < 0) throw py::error_already_set();  // an answer with no truth value
          if (truth == 0) thread.stop();
        } catch (py::error_already_set& e) {
          thread.stop();
          stopped = e.value();
        }
      }
      thread.acknowledge(reported);
      if (!stopped && PyErr_CheckSignals() != 0) {
        thread.stop();
        py::error_already_set e;
        stopped = e.value();
      }
    }
    py::gil_scoped_release unlocked;
    result.emplace(thread.take());
  }
  const int threads = opt.threads;
  auto frame =
      std::make_shared<Frame>(Rendered{scene, settings, plan, std::move(*result), threads});
  if (stopped) {
    // The finished passes go with the exception (docs/python.md).
    stopped.attr("frame") = py::cast(frame);
    PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(stopped.ptr())), stopped.ptr());
    throw py::error_already_set();
  }
  return frame;
}

}  // namespace

void bindScene(py::module_& m) {
  py::class_<PyScene>(m, "Scene",
                      "A scene loaded once (load_scene, Scene.from_dict), rendered any number of "
                      "times with any settings")
      .def_static(
          "from_dict",
          [](const py::object& d, const std::optional<std::string>& baseDir) {
            const std::string text = toJson(d).dump(1);
            const std::string dir = baseDir ? *baseDir : std::filesystem::current_path().string();
            py::gil_scoped_release unlocked;
            return PyScene{std::make_shared<const Scene>(loadSceneText(text, "<dict>", dir))};
          },
          py::arg("scene"), py::arg("base_dir") = py::none(),
          "A scene given as the JSON format's dicts and lists (docs/scene-format.md); mesh "
          "files resolve against base_dir (default: the current directory). Mistakes raise "
          "SceneError with the JSON path, and the line of the dict written out one key a line "
          "(file '<dict>').")
      .def_property_readonly("width", [](const PyScene& s) { return s.scene->render.width; })
      .def_property_readonly("height", [](const PyScene& s) { return s.scene->render.height; })
      .def_property_readonly("spp", [](const PyScene& s) { return s.scene->render.spp; })
      .def_property_readonly("seed", [](const PyScene& s) { return s.scene->render.seed; })
      .def_property_readonly(
          "sampler",
          [](const PyScene& s) { return std::string(samplerName(s.scene->render.sampler)); })
      .def_property_readonly("source", [](const PyScene& s) { return s.scene->sourcePath; })
      .def_property_readonly("features_used",
                             [](const PyScene& s) { return s.scene->features.used(); })
      .def(
          "render",
          [](const PyScene& s, std::optional<int64_t> spp, const py::object& seed,
             std::optional<int64_t> threads, std::optional<std::vector<int64_t>> crop,
             std::optional<std::vector<std::string>> aovs, std::optional<std::string> sampler,
             std::optional<double> targetRmse, std::optional<double> targetRelmse,
             std::optional<double> timeLimit, std::optional<int64_t> minSpp,
             std::optional<int64_t> maxSpp, const py::object& progress,
             std::optional<int64_t> width, std::optional<int64_t> height,
             std::optional<int64_t> maxDepth, const std::string& accel,
             const std::string& integrator, bool resumable) {
            RenderRequest q{spp,          seedOf(seed),
                            threads,      width,
                            height,       maxDepth,
                            minSpp,       maxSpp,
                            crop,         aovs.value_or(std::vector<std::string>{}),
                            sampler,      targetRmse,
                            targetRelmse, timeLimit,
                            accel,        integrator,
                            resumable};
            return render(s, q, progress);
          },
          py::kw_only(), py::arg("spp") = py::none(), py::arg("seed") = py::none(),
          py::arg("threads") = py::none(), py::arg("crop") = py::none(),
          py::arg("aovs") = py::none(), py::arg("sampler") = py::none(),
          py::arg("target_rmse") = py::none(), py::arg("target_relmse") = py::none(),
          py::arg("time_limit") = py::none(), py::arg("min_spp") = py::none(),
          py::arg("max_spp") = py::none(), py::arg("progress") = py::none(),
          py::arg("width") = py::none(), py::arg("height") = py::none(),
          py::arg("max_depth") = py::none(), py::arg("accel") = "embree",
          py::arg("integrator") = "production", py::arg("resumable") = false,
          "Renders the scene as `glint render` does with the same settings (the same pixels) "
          "and returns a Frame. progress(info) is called after each pass with a dict (pass, "
          "spp, seconds, estimated_rmse, ...); returning False cancels the render, which then "
          "returns the partial frame. Ctrl-C raises KeyboardInterrupt whose .frame holds the "
          "passes finished. The GIL is released while rendering.");
  m.def(
      "load_scene",
      [](const py::object& given) {
        const std::string path = pathOf(given);
        if (path.empty())
          throw py::value_error(
              "load_scene needs a path (default_scene() is the "
              "bundled scene)");
        py::gil_scoped_release unlocked;
        return PyScene{std::make_shared<const Scene>(loadSceneOrDefault(path))};
      },
      py::arg("path"),
      "Loads a scene file (JSON) or any mesh or scene file Glint reads (glTF, OBJ, PLY, ...), "
      "as `glint render PATH` does; mistakes raise SceneError (file, line, path).");
  m.def(
      "default_scene",
      [] {
        py::gil_scoped_release unlocked;
        return PyScene{std::make_shared<const Scene>(loadSceneOrDefault(""))};
      },
      "The bundled default scene, which `glint render` renders without a SCENE");
}

// For glint.validate.
const Scene& sceneOf(const py::object& scene) {
  // Not pybind11's "Unable to cast Python instance" for a path or a number.
  if (!py::isinstance<PyScene>(scene))
    throw py::type_error("scene must be a glint.Scene (glint.load_scene(path) reads a file), not " +
                         std::string(py::str(py::type::of(scene).attr("__name__"))));
  return *scene.cast<const PyScene&>().scene;
}

}  // namespace glint::python
