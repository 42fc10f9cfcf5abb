#pragma once
// What a Collada file must pass before Assimp's reader sees it. That reader trusts the file: an
// index list (<p>) holding any character but digits, signs and white space made it loop
// forever, appending to a list until memory ran out; and it reserves memory for every count a
// file declares (count="4000000000" on a <triangles> or an array) before reading a value.
#include <string>

namespace glint {

// Throws GlintError naming `path` and the line when `bytes` (the whole file) has a count or
// stride attribute that is not a whole number of at most the file's size (each counted item
// takes at least a byte), a <p> whose content is other than whole numbers and white space (or
// holds markup), or a <vcount> whose numbers add up past the file's size.
void checkColladaCounts(const std::string& path, const std::string& bytes);

}  // namespace glint
