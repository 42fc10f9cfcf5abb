#pragma once
// SIGINT and SIGTERM (Ctrl-C, Slurm's kill with its grace period) end Glint promptly in every
// phase, with exit 130 (CLI.md). Outside a render they end the process at once from the handler,
// after removing the temporary file being written, if any: nothing was rendered that a partial
// frame could keep. While a render runs (RenderPhase) they only raise the flag the render loop
// polls between chunks of camera samples, so the frame rendered so far is still written; a
// watchdog (Sampling) ends the process if the loop does not stop in time. A second signal
// always ends the process at once.
#include <atomic>
#include <string>

namespace glint::interrupt {

inline constexpr int kExitCode = 130;

// Installs the handlers; main() calls it first, so that loading a scene is covered too.
void install();

// Whether a signal asked the render to stop. The render loop polls it.
const std::atomic<bool>& requested();

// main()'s last word: after a stop that a signal asked for, the exit code is 130 (even when the
// signal came too late to cut the frame short), and after SIGINT the process ends by SIGINT
// itself, as shells expect of an interrupted command.
int finish(int exitCode);

// Removes the TemporaryFile now registered, if any: for other ways of ending the process at
// once (core/out_of_memory.h). Async-signal-safe.
void removeTemporaryFile();

// While one exists, a signal asks the render to stop instead of ending the process.
class RenderPhase {
 public:
  RenderPhase();
  ~RenderPhase();
  RenderPhase(const RenderPhase&) = delete;
  RenderPhase& operator=(const RenderPhase&) = delete;
};

// While one exists (around the render loop), a signal that asks the render to stop must be
// seen within a bound (kStopSeconds): a render thread waiting inside a library (OpenImageIO's
// cache waiting for a tile that a failed read will never deliver) never polls the flag. Past
// the bound the process ends with 130, as while loading, without writing the frame.
inline constexpr unsigned kStopSeconds = 10;
void setStopBound(unsigned seconds);  // for tests: a shorter bound
class Sampling {
 public:
  Sampling();
  ~Sampling();
  Sampling(const Sampling&) = delete;
  Sampling& operator=(const Sampling&) = delete;
};

// While one exists, a signal that ends the process removes `path` first (a temporary file
// that would otherwise outlive an interrupted write). One at a time; `path` up to PATH_MAX.
class TemporaryFile {
 public:
  explicit TemporaryFile(const std::string& path);
  ~TemporaryFile();
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
};

}  // namespace glint::interrupt
