#pragma once
// The colour tag a display image carries for the display it was made for (film/image_file.h):
// the displays of the bundled config and the usual names studio configs give the same
// displays, matched by name.
#include <string>
#include <vector>

#include "film/image_file.h"

namespace glint {

// The tag for the first of `names` (a view's display colour space, then its display, e.g.
// "sRGB - Display", "sRGB") that names a known display, matched without case, spaces,
// punctuation or a " - Display" ending; kind None when none does.
ColourTag colourTagForDisplay(const std::vector<std::string>& names);

}  // namespace glint
