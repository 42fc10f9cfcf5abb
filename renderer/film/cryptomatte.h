#pragma once
// Cryptomatte (Friedman & Jones, Psyop; specification 1.2.0): ID mattes that a compositor
// (Nuke's and Fusion's Cryptomatte nodes, Blender's Cryptomatte node) extracts by name. Each
// name is hashed with MurmurHash3_x86_32 and the hash stored as a float32 ID; a pixel keeps its
// (ID, coverage) pairs, sorted by coverage, two per RGBA layer {type}00, {type}01, ...; the
// file's metadata names the type, the hash, the conversion and the manifest (name → ID).
// docs/output.md says which names Glint uses.
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "film/film.h"

namespace glint {

// Ranks (ID, coverage pairs) written per pixel and type: the specification's suggested
// default, 3 layers.
inline constexpr int kCryptomatteRanks = 6;

// The specification's uint32_to_float32: the hash's bits as a float, except that an exponent of
// 0 (zero, denormals) or 255 (inf, NaN) has its lowest bit flipped, making it 1 or 254.
float cryptomatteIdFromHash(uint32_t hash);
// MurmurHash3_x86_32 of the name (its bytes, seed 0), converted.
float cryptomatteId(std::string_view name);
// The 8 hex digits of the ID's float bits, as the manifest writes them ("%08x").
std::string cryptomatteHex(float id);
// The metadata key of a type: the first 7 hex digits of the hex of its name's ID, as the
// reference Nuke plugin makes it (cryptomatte_utilities.layer_hash).
std::string cryptomatteKey(std::string_view typeName);
// The manifest: a JSON object {name: hex} of every name (duplicates once).
std::string cryptomatteManifest(const std::vector<std::string>& names);

// Adds the layers {type}00 ... of kCryptomatteRanks ranks (channels R, G, B, A = ID, coverage
// of two ranks, float) to the film, and the type's metadata: cryptomatte/KEY/name, hash,
// conversion and manifest (of `names`), and glint:cryptomatte_depth (the rank count). Returns
// the index of the first plane; the others follow it.
size_t addCryptomatteLayers(Film& film, const std::string& typeName,
                            const std::vector<std::string>& names);

}  // namespace glint
