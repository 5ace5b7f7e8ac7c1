// The Radiance HDR reader against stb's on complete files, and on every way a file can be cut
// short or corrupted: each must be an Error naming the file and what is missing, never a hang or
// a crash (stb's reader spins forever on some truncated maps, which is why we have our own).
#include "image/ImageIO.h"
#include "image/RadianceHdr.h"
#include "support/TestFiles.h"

#include <cstring>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <stb_image.h>
#include <vector>

using namespace bl;
using bl::test::errorOf;
using bl::test::sharedPath;
using Bytes = std::vector<unsigned char>;

namespace {

Bytes readBytes(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    return Bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

std::string writeBytes(const std::string& name, const Bytes& bytes) {
    return bl::test::writeTempFile(name, std::string(bytes.begin(), bytes.end()));
}

// stb's decoding of a complete, valid file: the pixels ours must reproduce bit for bit.
Image stbDecode(const Bytes& bytes) {
    int w = 0, h = 0, n = 0;
    float* data = stbi_loadf_from_memory(bytes.data(), int(bytes.size()), &w, &h, &n, 3);
    EXPECT_NE(data, nullptr) << stbi_failure_reason();
    Image image(w, h);
    if (data) std::memcpy(image.pixels().data(), data, sizeof(float) * 3 * std::size_t(w) * h);
    stbi_image_free(data);
    return image;
}

void expectSamePixels(const Image& ours, const Image& stb) {
    ASSERT_EQ(ours.width(), stb.width());
    ASSERT_EQ(ours.height(), stb.height());
    std::size_t differ = 0;
    for (std::size_t i = 0; i < ours.pixelCount(); ++i) {
        differ += std::memcmp(&ours.pixels()[i], &stb.pixels()[i], sizeof(glm::vec3)) != 0;
    }
    EXPECT_EQ(differ, 0u) << "of " << ours.pixelCount() << " pixels";
}

Bytes header(int w, int h) {
    const std::string s = "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(h) + " +X " + std::to_string(w) + "\n";
    return Bytes(s.begin(), s.end());
}

// A w x h image whose pixel (x, y) has mantissas from (x, y) and exponent 128 + (x + y) % 5.
unsigned char texel(int x, int y, int c) { return c == 3 ? (x + y) % 5 == 4 ? 0 : 128 + (x + y) % 5 : (37 * x + 11 * y + 90 * c) % 256; }

// New-style RLE: each scanline a 2,2,width marker, then every plane as a run of its first byte
// (count 2) followed by dumps of at most 128, so both kinds of record are exercised.
Bytes encodeRle(int w, int h) {
    Bytes out = header(w, h);
    for (int y = 0; y < h; ++y) {
        out.insert(out.end(), {2, 2, static_cast<unsigned char>(w >> 8), static_cast<unsigned char>(w & 0xff)});
        for (int c = 0; c < 4; ++c) {
            out.insert(out.end(), {128 + 2, texel(0, y, c)}); // pixels 0 and 1 alike
            for (int x = 2; x < w;) {
                const int n = std::min(128, w - x);
                out.push_back(static_cast<unsigned char>(n));
                for (int i = 0; i < n; ++i) out.push_back(texel(x + i, y, c));
                x += n;
            }
        }
    }
    return out;
}

Bytes encodeFlat(int w, int h) {
    Bytes out = header(w, h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            for (int c = 0; c < 4; ++c) out.push_back(texel(x, y, c));
    return out;
}

// Decoding the first `length` bytes must fail with an error that names the file, says it is
// truncated and says which part is missing.
void expectTruncationError(const Bytes& bytes, std::size_t length, const std::string& name) {
    const std::string error = errorOf([&] {
        decodeRadianceHdr(std::span<const unsigned char>(bytes.data(), length), name);
    });
    ASSERT_EQ(error.rfind(name + ": Radiance HDR: ", 0), 0u) << "length " << length << ": '" << error << "'";
    ASSERT_NE(error.find("truncated"), std::string::npos) << "length " << length << ": " << error;
    const bool saysWhat = error.find("scanline") != std::string::npos || error.find("header") != std::string::npos ||
                          error.find("magic line") != std::string::npos ||
                          error.find("resolution line") != std::string::npos ||
                          error.find("need at least") != std::string::npos;
    ASSERT_TRUE(saysWhat) << "length " << length << ": " << error;
}

} // namespace

TEST(RadianceHdr, RealMapsDecodeToStbsPixels) {
    BL_SKIP_WITHOUT_SHARED("data/envmap/classroom-sky.hdr");
    BL_SKIP_WITHOUT_SHARED("data/envmap/vogl-probe.hdr");
    for (const char* map : {"data/envmap/classroom-sky.hdr", "data/envmap/vogl-probe.hdr"}) {
        SCOPED_TRACE(map);
        const Bytes bytes = readBytes(sharedPath(map));
        ASSERT_GT(bytes.size(), 1000u);
        expectSamePixels(readImage(sharedPath(map)), stbDecode(bytes));
    }
}

TEST(RadianceHdr, SyntheticRleAndFlatFilesDecodeToStbsPixels) {
    for (const Bytes& bytes : {encodeRle(300, 3), encodeFlat(300, 3), encodeFlat(5, 4)}) {
        const Image ours = decodeRadianceHdr(bytes, "synthetic.hdr");
        expectSamePixels(ours, stbDecode(bytes));
        EXPECT_GT(ours.mean().x, 0.0); // not trivially black
    }
}

// Every truncation of a real map: all lengths through the header and the first scanlines, a
// stride over the rest, and the last 64 (the end of the last scanline).
TEST(RadianceHdr, EveryTruncationOfARealMapIsAClearError) {
    BL_SKIP_WITHOUT_SHARED("data/envmap/classroom-sky.hdr");
    const std::string name = sharedPath("data/envmap/classroom-sky.hdr");
    const Bytes bytes = readBytes(name);
    // 32 KiB: the header, the lengths refused up front (fewer bytes than 512 scanlines can take)
    // and then the first ~16 scanlines (820 bytes each on average), decoded until they run out.
    const std::size_t exhaustive = std::min<std::size_t>(32768, bytes.size());
    std::size_t tried = 0;
    for (std::size_t n = 0; n < exhaustive; ++n, ++tried) expectTruncationError(bytes, n, name);
    for (std::size_t n = exhaustive; n + 64 < bytes.size(); n += 1009, ++tried) expectTruncationError(bytes, n, name);
    for (std::size_t n = bytes.size() - 64; n < bytes.size(); ++n, ++tried) expectTruncationError(bytes, n, name);
    EXPECT_GT(tried, 33000u);
    EXPECT_NO_THROW(decodeRadianceHdr(bytes, name));
}

TEST(RadianceHdr, EveryTruncationOfSmallRleAndFlatFilesIsAClearError) {
    for (const Bytes& bytes : {encodeRle(300, 3), encodeFlat(5, 4)}) {
        for (std::size_t n = 0; n < bytes.size(); ++n) expectTruncationError(bytes, n, "small.hdr");
    }
}

TEST(RadianceHdr, TruncatedFileOnDiskIsAnErrorThroughReadImage) {
    BL_SKIP_WITHOUT_SHARED("data/envmap/classroom-sky.hdr");
    const Bytes bytes = readBytes(sharedPath("data/envmap/classroom-sky.hdr"));
    for (std::size_t n : {std::size_t(5), std::size_t(60), bytes.size() / 2, bytes.size() - 1}) {
        const std::string path = writeBytes("cut.hdr", Bytes(bytes.begin(), bytes.begin() + std::ptrdiff_t(n)));
        const std::string error = errorOf([&] { readImage(path); });
        EXPECT_NE(error.find(path), std::string::npos) << error;
        EXPECT_NE(error.find("truncated"), std::string::npos) << error;
    }
}

TEST(RadianceHdr, CorruptRunLengthsAreErrors) {
    const int w = 300;
    const std::size_t firstRecord = header(w, 3).size() + 4; // the R plane's first record
    struct Case {
        std::vector<unsigned char> record; // replaces the first record (its count and value)
        const char* expected;
    };
    for (const Case& c : std::vector<Case>{{{128, 0}, "corrupt run length 0"}, // a run of 0
                                           {{0, 0}, "corrupt run length 0"}}) {  // a dump of 0
        Bytes bytes = encodeRle(w, 3);
        std::copy(c.record.begin(), c.record.end(), bytes.begin() + std::ptrdiff_t(firstRecord));
        const std::string error = errorOf([&] { decodeRadianceHdr(bytes, "corrupt.hdr"); });
        EXPECT_EQ(error.rfind("corrupt.hdr: Radiance HDR: ", 0), 0u) << error;
        EXPECT_NE(error.find(c.expected), std::string::npos) << error;
    }
    // A run longer than the pixels left in its scanline.
    {
        Bytes bytes = encodeRle(8, 2);
        bytes[header(8, 2).size() + 4] = 128 + 9; // 9 > 8 pixels
        EXPECT_NE(errorOf([&] { decodeRadianceHdr(bytes, "long.hdr"); }).find("corrupt run length 9"),
                  std::string::npos);
    }
    // A scanline marker with the wrong width, and a later scanline without a marker.
    {
        Bytes bytes = encodeRle(w, 3);
        bytes[header(w, 3).size() + 3] ^= 1;
        EXPECT_NE(errorOf([&] { decodeRadianceHdr(bytes, "w.hdr"); }).find("pixels wide"), std::string::npos);
    }
    {
        Bytes bytes = encodeRle(w, 3);
        const std::size_t perLine = (bytes.size() - header(w, 3).size()) / 3;
        bytes[header(w, 3).size() + perLine] = 7;
        EXPECT_NE(errorOf([&] { decodeRadianceHdr(bytes, "m.hdr"); }).find("no run-length marker"), std::string::npos);
    }
}

TEST(RadianceHdr, HeaderErrorsNameWhatIsWrong) {
    auto decode = [](const std::string& s) {
        return errorOf([&] { decodeRadianceHdr(Bytes(s.begin(), s.end()), "h.hdr"); });
    };
    EXPECT_NE(decode("P6\n1 1\n255\n").find("#?RADIANCE"), std::string::npos);
    EXPECT_NE(decode("#?RADIANCE\nFORMAT=32-bit_rle_xyze\n\n-Y 1 +X 1\nabcd").find("xyze"), std::string::npos);
    EXPECT_NE(decode("#?RADIANCE\n\n+Y 1 +X 1\nabcd").find("orientations"), std::string::npos);
    EXPECT_NE(decode("#?RADIANCE\n\n-Y 0 +X 1\n").find("outside"), std::string::npos);
    // A corrupt resolution asks for more pixels than the file can hold: refused before allocating.
    EXPECT_NE(decode("#?RADIANCE\n\n-Y 16000000 +X 16000000\nabcd").find("need at least"), std::string::npos);
    EXPECT_NE(decode("#?RADIANCE\n" + std::string(2000, 'x')).find("longer than"), std::string::npos);
}
