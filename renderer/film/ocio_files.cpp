#include "film/ocio_files.h"

#include "core/error.h"
#include "core/input_files.h"

namespace OCIO = OCIO_NAMESPACE;

namespace glint {

namespace {

void checkTransform(const OCIO::ConstConfigRcPtr& config, const OCIO::ConstTransformRcPtr& t,
                    const std::string& where) {
  if (!t) return;
  if (const auto group = OCIO::DynamicPtrCast<const OCIO::GroupTransform>(t)) {
    for (int i = 0; i < group->getNumTransforms(); ++i)
      checkTransform(config, group->getTransform(i), where);
    return;
  }
  const auto file = OCIO::DynamicPtrCast<const OCIO::FileTransform>(t);
  if (!file || !file->getSrc()) return;
  const std::string src = file->getSrc();
  checkPathCharacters(src, where + ": its FileTransform");
  std::string resolved;
  try {
    resolved = config->getCurrentContext()->resolveFileLocation(src.c_str());
  } catch (const OCIO::Exception&) {
    return;  // not found: OCIO says so if a processor needs it
  }
  checkInputFile(resolved, kMaxOcioFileBytes, where + ": its FileTransform's file");
}

}  // namespace

void checkOcioConfigFiles(const OCIO::ConstConfigRcPtr& config, const std::string& source) {
  const std::string in = "OCIO (" + source + "): ";
  for (int i = 0;
       i < config->getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL); ++i) {
    const char* name =
        config->getColorSpaceNameByIndex(OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL, i);
    const auto space = config->getColorSpace(name);
    if (!space) continue;
    for (const auto dir : {OCIO::COLORSPACE_DIR_TO_REFERENCE, OCIO::COLORSPACE_DIR_FROM_REFERENCE})
      checkTransform(config, space->getTransform(dir), in + "colour space " + inQuotes(name));
  }
  for (int i = 0; i < config->getNumLooks(); ++i) {
    const char* name = config->getLookNameByIndex(i);
    const auto look = config->getLook(name);
    if (!look) continue;
    checkTransform(config, look->getTransform(), in + "look " + inQuotes(name));
    checkTransform(config, look->getInverseTransform(), in + "look " + inQuotes(name));
  }
  for (int i = 0; i < config->getNumViewTransforms(); ++i) {
    const char* name = config->getViewTransformNameByIndex(i);
    const auto view = config->getViewTransform(name);
    if (!view) continue;
    for (const auto dir :
         {OCIO::VIEWTRANSFORM_DIR_TO_REFERENCE, OCIO::VIEWTRANSFORM_DIR_FROM_REFERENCE})
      checkTransform(config, view->getTransform(dir), in + "view transform " + inQuotes(name));
  }
  for (int i = 0; i < config->getNumNamedTransforms(OCIO::NAMEDTRANSFORM_ALL); ++i) {
    const char* name = config->getNamedTransformNameByIndex(OCIO::NAMEDTRANSFORM_ALL, i);
    const auto named = config->getNamedTransform(name);
    if (!named) continue;
    for (const auto dir : {OCIO::TRANSFORM_DIR_FORWARD, OCIO::TRANSFORM_DIR_INVERSE})
      checkTransform(config, named->getTransform(dir), in + "named transform " + inQuotes(name));
  }
}

}  // namespace glint
