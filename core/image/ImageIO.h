// Reading and writing images. EXR holds linear radiance (float32, AOVs as named layers, run
// metadata as string attributes); PNG is an 8-bit sRGB preview only.
#pragma once

#include "image/Image.h"

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace bl {

struct ImageLayer {
    std::string name; // "" is the main RGB image; others become "<name>.R" etc.
    const Image* image;
};

// Writes atomically (temporary file, then rename) so a crash never leaves half an image.
void writeExr(const std::string& path, const std::vector<ImageLayer>& layers,
              const std::map<std::string, std::string>& attributes = {});
void writeExr(const std::string& path, const Image& image);

// Linear radiance -> 8-bit sRGB (alpha 255), scaled by 2^exposure and clamped; non-finite pixels
// turn magenta so that they are seen. The PNG preview's and the viewer's tonemap.
Rgba8Image toSrgb8(const Image& image, float exposure = 0.0f);

// The sRGB preview of linear radiance: toSrgb8, written as an RGB PNG.
void writePng(const std::string& path, const Image& image, float exposure = 0.0f);
// An 8-bit image as an RGB PNG (alpha dropped).
void writePng(const std::string& path, const Rgba8Image& image);

// Portable float map (RGB float32, little-endian): a float image any script can read (numpy) where
// no EXR reader exists. Written atomically.
void writePfm(const std::string& path, const Image& image);

// Reads the main RGB layer (or the named layer) of an EXR, a Radiance .hdr (our bounds-checked
// reader, image/RadianceHdr.h, by extension or magic line), or an 8-bit image (PNG/JPEG/…, decoded
// from sRGB to linear). Errors name the file.
Image readImage(const std::string& path, const std::string& layer = "");

// Reads an 8-bit texture without decoding, for the GPU's sRGB formats.
Rgba8Image readRgba8(const std::string& path);

// Layer names of an EXR ("" for the main R,G,B).
std::vector<std::string> exrLayers(const std::string& path);

} // namespace bl
