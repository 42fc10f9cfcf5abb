#include "app/accel_options.h"

#include "app/commands.h"

namespace glint {

void addAccelOptions(CLI::App& cmd, AccelOptions& options) {
  RayClassSettings& rc = options.rayclass;
  cmd.add_option("--rayclass-n-min", rc.nMin,
                 "rayclass: split no cell whose candidate list holds at most this many objects "
                 "(seed 002's n_min; default " +
                     std::to_string(rc.nMin) + ")")
      ->check(wholeNumberUpTo(1u << 30));
  // Below 1e-6 the cells would be about 100 levels deep.
  cmd.add_option("--rayclass-w-min", rc.wMin,
                 "rayclass: split no cell at most this wide in its narrowest axis, E scaled to a "
                 "unit cube (seed 002's w_min; 1 splits nothing; default " +
                     defaultText(rc.wMin) + ")")
      ->check(CLI::Range(1e-6, 1.0) & notNaN());
}

}  // namespace glint
