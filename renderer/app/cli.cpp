#include <glint_version.h>

#include <algorithm>
#include <map>
#include <vector>

#include "app/commands.h"
#include "app/option_arity.h"
#include "core/error.h"
#include "core/log.h"
#include "core/out_of_memory.h"

namespace glint {

namespace {
std::string gCommandLine;
}

const std::string& commandLine() { return gCommandLine; }

int runCli(int argc, char** argv) {
  for (int i = 0; i < argc; ++i) gCommandLine += (i ? " " : "") + std::string(argv[i]);
  CLI::App app{"Glint: a Whitted / distribution ray tracer on Embree", "glint"};
  app.set_version_flag("--version", std::string("glint ") + GLINT_VERSION);
  app.require_subcommand(1);
  std::map<CLI::App*, CommandRunner> runners;
  const auto add = [&](CommandRunner runner) {
    runners[app.get_subcommands({}).back()] = std::move(runner);
  };
  add(addRenderCommand(app));
  add(addValidateCommand(app));
  add(addCompareCommand(app));
  add(addConvergeCommand(app));
  add(addMergeCommand(app));
  add(addPlanCommand(app));
  add(addConvertCommand(app));
  add(addBenchCommand(app));
  add(addInfoCommand(app));

  std::vector<std::string> args(argv + std::min(argc, 1), argv + argc);
  try {
    args = checkArities(app, std::move(args));
  } catch (const UsageError& e) {
    log::error(e.what());
    return kExitUsage;
  }
  std::reverse(args.begin(), args.end());  // CLI11 takes them last first
  try {
    app.parse(std::move(args));
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? kExitOk : kExitUsage;
  }
  try {
    for (auto& [sub, run] : runners)
      if (sub->parsed()) return run();
  } catch (const SceneError& e) {
    log::error(e.what());
    return kExitUsage;
  } catch (const UsageError& e) {
    log::error(e.what());
    return kExitUsage;
  } catch (const GlintError& e) {
    log::error(e.what());
    return kExitRuntime;
  } catch (const std::bad_alloc&) {
    log::error(out_of_memory::message());
    return kExitRuntime;
  } catch (const std::exception& e) {
    if (out_of_memory::isResourceShortage(e))
      log::error(out_of_memory::message() + " (" + e.what() + ")");
    else
      log::error(e.what());
    return kExitRuntime;
  }
  return kExitUsage;
}

}  // namespace glint
