// Text drawn over the viewer's frame (image/ImageIO.h's toSrgb8 makes the frame): stb_easy_font's
// glyph rectangles, white on a dark backing.
#pragma once

#include "image/Image.h"

#include <string>

namespace bl::viewer {

// Draws `text` (lines split at '\n') with its top-left corner at (x, y), `scale` pixels per font
// unit.
void drawText(Rgba8Image& frame, int x, int y, const std::string& text, int scale = 1);

} // namespace bl::viewer
