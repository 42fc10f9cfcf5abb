#pragma once
// What an ASCII FBX file must pass before Assimp's reader sees it. That reader decodes a texture
// embedded in the file (a Video's Content: quoted base64 strings) without checking its
// characters: a byte outside base64's alphabet, or padding before a string's end, made it write
// past its buffer and crash (SIGSEGV, or glibc's "double free or corruption").
#include <string>

namespace glint {

// Throws GlintError naming `path`, the line and the byte when `bytes` (the whole file) is an
// ASCII FBX file whose Content properties hold a string that is not base64 (RFC 4648: its
// alphabet, a length that is a multiple of 4, at most two '=' and only at the end), or an
// unterminated string. A binary FBX file (its embedded textures raw bytes) passes.
void checkFbxEmbeddedContent(const std::string& path, const std::string& bytes);

}  // namespace glint
