#include "image/RadianceHdr.h"

#include "base/Error.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string_view>
#include <vector>

namespace bl {
namespace {

// Scanlines of 8 to 32767 pixels may be run-length encoded: the 15-bit width in the scanline's
// 4-byte marker bounds it, and Radiance writes narrower ones flat.
constexpr int kMinRleWidth = 8;
constexpr int kMaxRleWidth = 0x7fff;
// A header line longer than this is not a Radiance header (stb reads 1024-byte lines).
constexpr std::size_t kMaxHeaderLine = 1024;
// 2^24 pixels on a side, as stb allows; the pixel count is bounded by the bytes in the file.
constexpr long kMaxSide = 1L << 24;

// Where the pixel data is being read, for error messages.
struct Position {
    int row = 0, height = 0, pixel = 0, width = 0, plane = -1;
};

std::string describe(const Position& p) {
    return "scanline " + std::to_string(p.row) + " of " + std::to_string(p.height) + " (" +
           (p.plane >= 0 ? std::string("byte plane ") + "RGBE"[p.plane] + ", " : std::string()) + "pixel " +
           std::to_string(p.pixel) + " of " + std::to_string(p.width) + ")";
}

class Reader {
public:
    Reader(std::span<const unsigned char> bytes, const std::string& name) : mBytes(bytes), mName(name) {}

    std::size_t offset() const { return mPos; }
    std::size_t left() const { return mBytes.size() - mPos; }

    [[noreturn]] void fail(const std::string& what) const { throw Error(mName + ": Radiance HDR: " + what); }

    // One header line without its '\n'; `what` names the line for the error when it is cut short.
    std::string_view line(const std::string& what) {
        const std::size_t start = mPos;
        while (mPos < mBytes.size() && mBytes[mPos] != '\n') {
            if (mPos - start >= kMaxHeaderLine) {
                fail(what + " at byte " + std::to_string(start) + " is longer than " +
                     std::to_string(kMaxHeaderLine) + " bytes: not a Radiance header");
            }
            ++mPos;
        }
        if (mPos == mBytes.size()) {
            fail("the file ends inside " + what + " (" + std::to_string(mBytes.size()) +
                 " bytes): truncated before the pixels");
        }
        std::string_view s(reinterpret_cast<const char*>(mBytes.data()) + start, mPos - start);
        ++mPos; // the '\n'
        if (!s.empty() && s.back() == '\r') s.remove_suffix(1);
        return s;
    }

    // `n` bytes of the pixel data at `at`, or a truncation error saying where the data stops.
    const unsigned char* take(std::size_t n, const Position& at) {
        if (n > left()) {
            fail("truncated: the file ends at byte " + std::to_string(mBytes.size()) + " inside " + describe(at));
        }
        const unsigned char* bytes = mBytes.data() + mPos;
        mPos += n;
        return bytes;
    }

private:
    std::span<const unsigned char> mBytes;
    const std::string& mName;
    std::size_t mPos = 0;
};

// Radiance's conversion (and stb's, bit for bit): mantissa * 2^(e - 128 - 8); e = 0 is black.
glm::vec3 rgbeToFloat(const unsigned char* rgbe) {
    if (rgbe[3] == 0) return glm::vec3(0.0f);
    const auto f = static_cast<float>(std::ldexp(1.0f, int(rgbe[3]) - (128 + 8)));
    return {rgbe[0] * f, rgbe[1] * f, rgbe[2] * f};
}

void readHeader(Reader& in) {
    const std::string_view magic = in.line("the magic line");
    if (magic != "#?RADIANCE" && magic != "#?RGBE") {
        in.fail("the first line is not #?RADIANCE or #?RGBE");
    }
    for (int n = 1;; ++n) {
        const std::string_view s = in.line("header line " + std::to_string(n) + " (no empty line ends the header)");
        if (s.empty()) return;
        if (s.starts_with("FORMAT=") && s != "FORMAT=32-bit_rle_rgbe") {
            in.fail("unsupported " + std::string(s) + " (only 32-bit_rle_rgbe is read)");
        }
    }
}

// Parses "-Y H +X W" exactly: other orientations are valid Radiance but no tool we read writes them.
glm::ivec2 readResolution(Reader& in) {
    const std::string text(in.line("the resolution line"));
    long h = 0, w = 0;
    int used = 0;
    if (std::sscanf(text.c_str(), "-Y %ld +X %ld%n", &h, &w, &used) != 2 || used != int(text.size())) {
        in.fail("resolution line '" + text + "' is not '-Y <height> +X <width>' (other orientations are not read)");
    }
    if (w < 1 || h < 1 || w > kMaxSide || h > kMaxSide) {
        in.fail("resolution " + std::to_string(w) + "x" + std::to_string(h) + " is outside 1.." +
                std::to_string(kMaxSide));
    }
    return {int(w), int(h)};
}

void readFlat(Reader& in, Image& image, int firstRow) {
    Position p{firstRow, image.height(), 0, image.width()};
    for (; p.row < image.height(); ++p.row) {
        for (p.pixel = 0; p.pixel < image.width(); ++p.pixel) {
            image.at(p.pixel, p.row) = rgbeToFloat(in.take(4, p));
        }
    }
}

// One new-style RLE scanline after its 4-byte marker: four byte planes of runs (count > 128:
// one byte repeated count - 128 times) and dumps (count <= 128 literal bytes).
void readRleScanline(Reader& in, Position& p, std::vector<unsigned char>& planes) {
    const int w = p.width;
    for (p.plane = 0; p.plane < 4; ++p.plane) {
        unsigned char* plane = planes.data() + std::size_t(p.plane) * w;
        for (p.pixel = 0; p.pixel < w;) {
            int count = *in.take(1, p);
            const bool run = count > 128;
            if (run) count -= 128;
            if (count == 0 || count > w - p.pixel) {
                in.fail("corrupt run length " + std::to_string(count) + " at byte " + std::to_string(in.offset() - 1) +
                        " in " + describe(p) + ": " + std::to_string(w - p.pixel) + " pixels are left");
            }
            if (run) {
                const unsigned char value = *in.take(1, p);
                std::fill_n(plane + p.pixel, count, value);
            } else {
                const unsigned char* src = in.take(std::size_t(count), p);
                std::copy_n(src, count, plane + p.pixel);
            }
            p.pixel += count;
        }
    }
    p.plane = -1;
}

void readRle(Reader& in, Image& image) {
    const int w = image.width();
    std::vector<unsigned char> planes(std::size_t(w) * 4);
    Position p{0, image.height(), 0, w};
    for (; p.row < image.height(); ++p.row) {
        p.pixel = 0;
        const unsigned char* marker = in.take(4, p);
        if (marker[0] != 2 || marker[1] != 2 || (marker[2] & 0x80)) {
            if (p.row == 0) {
                // Not encoded: these four bytes are the first flat pixel (as Radiance and stb decide).
                image.at(0, 0) = rgbeToFloat(marker);
                Position q{0, image.height(), 1, w};
                for (; q.pixel < w; ++q.pixel) image.at(q.pixel, 0) = rgbeToFloat(in.take(4, q));
                readFlat(in, image, 1);
                return;
            }
            in.fail(describe(p) + " at byte " + std::to_string(in.offset() - 4) +
                    " has no run-length marker (2, 2, width) although the first scanline had one");
        }
        const int length = (int(marker[2]) << 8) | marker[3];
        if (length != w) {
            in.fail(describe(p) + " says it is " + std::to_string(length) + " pixels wide, the image is " +
                    std::to_string(w));
        }
        readRleScanline(in, p, planes);
        for (int x = 0; x < w; ++x) {
            const unsigned char rgbe[4] = {planes[x], planes[w + x], planes[2 * std::size_t(w) + x],
                                           planes[3 * std::size_t(w) + x]};
            image.at(x, p.row) = rgbeToFloat(rgbe);
        }
    }
}

} // namespace

bool isRadianceHdr(std::span<const unsigned char> bytes) {
    const std::string_view s(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return s.starts_with("#?RADIANCE") || s.starts_with("#?RGBE");
}

bool isRadianceHdrFile(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    unsigned char head[10] = {};
    f.read(reinterpret_cast<char*>(head), sizeof(head));
    return isRadianceHdr(std::span<const unsigned char>(head, std::size_t(f.gcount())));
}

Image decodeRadianceHdr(std::span<const unsigned char> bytes, const std::string& name) {
    Reader in(bytes, name);
    readHeader(in);
    const glm::ivec2 size = readResolution(in);
    // The least data the pixels can take (flat: 4 bytes each; RLE: a marker and one 2-byte run per
    // 128 pixels per plane and scanline), checked before allocating so that a corrupt resolution
    // line cannot ask for gigabytes.
    const bool mayRle = size.x >= kMinRleWidth && size.x <= kMaxRleWidth;
    const double perRow = mayRle ? 4.0 + 4.0 * 2.0 * std::ceil(size.x / 128.0) : 4.0 * size.x;
    if (perRow * size.y > double(in.left())) {
        in.fail("truncated: " + std::to_string(size.x) + "x" + std::to_string(size.y) + " pixels need at least " +
                std::to_string(std::uint64_t(perRow * size.y)) + " bytes of scanlines, the file has " +
                std::to_string(in.left()) + " after its header");
    }
    Image image(size.x, size.y);
    if (mayRle) {
        readRle(in, image);
    } else {
        readFlat(in, image, 0);
    }
    return image;
}

Image readRadianceHdr(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) {
        throw Error(path + ": cannot open");
    }
    const std::vector<unsigned char> bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    if (f.bad()) {
        throw Error(path + ": read error");
    }
    return decodeRadianceHdr(bytes, path);
}

} // namespace bl
