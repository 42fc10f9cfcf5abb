#pragma once
// A config whose colour spaces, looks or transforms refer to themselves, directly or round a
// loop (a look whose LookTransform applies that look, a colour space converted through
// itself), sends OCIO's processor builder into a recursion that overflows the stack. Glint
// follows the references first and refuses such a config.
#include <OpenColorIO/OpenColorIO.h>

#include <string>

namespace glint {

// Throws UsageError naming `source` (the config) and the loop ("look \"a\" → colour space
// \"b\" → look \"a\"") where the references among the config's colour spaces, looks, view
// transforms and named transforms close a loop: ColorSpaceTransform and LookTransform ends,
// LookTransform and display views' looks, looks' process spaces, DisplayViewTransform sources
// and views, through group transforms.
void checkOcioReferenceCycles(const OCIO_NAMESPACE::ConstConfigRcPtr& config,
                              const std::string& source);

}  // namespace glint
