// A bounds-checked reader of Radiance HDR (RGBE) images, the format of most environment maps.
// Ours rather than stb_image's because stb's reader spins forever on some truncated files (it
// reads zeros past the end of the data and loops on a run of length 0); every read here checks
// the bytes left, so a truncated or corrupt file is an Error naming the file and what is missing.
//
// Supported, as written by Radiance, HDR Shop, Photoshop and stb: the "#?RADIANCE" / "#?RGBE"
// magic line, header variables up to an empty line (FORMAT must be 32-bit_rle_rgbe when given;
// XYZE is refused), the standard resolution line "-Y H +X W" (rows top to bottom, columns left to
// right), and pixels either flat (4 bytes each) or as new-style run-length encoded scanlines
// (2, 2, width: then each of the four byte planes as runs and dumps). As in stb and Radiance,
// whether a file is run-length encoded is decided by its first scanline. Old-style RLE (1,1,1,n
// repeat markers) is not decoded, as in stb.
#pragma once

#include "image/Image.h"

#include <cstddef>
#include <span>
#include <string>

namespace bl {

// True when the bytes begin with the Radiance magic line ("#?RADIANCE" or "#?RGBE").
bool isRadianceHdr(std::span<const unsigned char> bytes);
bool isRadianceHdrFile(const std::string& path);

// Decodes a whole file held in memory; `name` (the path) heads every error message.
Image decodeRadianceHdr(std::span<const unsigned char> bytes, const std::string& name);

// Reads and decodes a file.
Image readRadianceHdr(const std::string& path);

} // namespace bl
