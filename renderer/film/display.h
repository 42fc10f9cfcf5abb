#pragma once
// A display image for people: the film's scene-linear RGB clamped to [0, 1] and encoded with
// the sRGB transfer function into an 8-bit PNG (OpenColorIO views replace this later).
#include <string>

#include "film/film.h"

namespace glint {

float srgbEncode(float linear);
void writeDisplayPng(const std::string& path, const Film& film);

}  // namespace glint
