#include "image/ImageIO.h"

#include "base/Error.h"
#include "image/RadianceHdr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <stb_image.h>
#include <stb_image_write.h>

namespace fs = std::filesystem;

namespace bl {
namespace {

std::string lowerExtension(const std::string& path) {
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    return ext;
}

void requireFile(const std::string& path) {
    if (!fs::is_regular_file(path)) {
        throw Error(path + ": file not found");
    }
}

std::string channelName(const std::string& layer, char c) {
    return layer.empty() ? std::string(1, c) : layer + "." + c;
}

// Renames the finished temporary file over the target, so readers never see a partial file.
void commitFile(const std::string& tmp, const std::string& path) {
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp);
        throw Error(path + ": cannot write: " + ec.message());
    }
}

} // namespace

void writeExr(const std::string& path, const std::vector<ImageLayer>& layers,
              const std::map<std::string, std::string>& attributes) {
    if (layers.empty() || !layers[0].image || layers[0].image->empty()) {
        throw Error(path + ": nothing to write");
    }
    const int w = layers[0].image->width();
    const int h = layers[0].image->height();
    Imf::Header header(w, h);
    Imf::FrameBuffer fb;
    for (const ImageLayer& layer : layers) {
        if (layer.image->width() != w || layer.image->height() != h) {
            throw Error(path + ": layer '" + layer.name + "' has a different size");
        }
        char* base = reinterpret_cast<char*>(const_cast<glm::vec3*>(layer.image->pixels().data()));
        for (int c = 0; c < 3; ++c) {
            std::string name = channelName(layer.name, "RGB"[c]);
            header.channels().insert(name, Imf::Channel(Imf::FLOAT));
            fb.insert(name, Imf::Slice(Imf::FLOAT, base + c * sizeof(float), sizeof(glm::vec3),
                                       sizeof(glm::vec3) * w));
        }
    }
    for (const auto& [key, value] : attributes) {
        header.insert(key, Imf::StringAttribute(value));
    }
    std::string tmp = path + ".tmp";
    try {
        Imf::OutputFile file(tmp.c_str(), header);
        file.setFrameBuffer(fb);
        file.writePixels(h);
    } catch (const std::exception& e) {
        fs::remove(tmp);
        throw Error(path + ": cannot write EXR: " + e.what());
    }
    commitFile(tmp, path);
}

void writeExr(const std::string& path, const Image& image) { writeExr(path, {{"", &image}}); }

Rgba8Image toSrgb8(const Image& image, float exposure) {
    const float scale = std::exp2(exposure);
    Rgba8Image out{image.width(), image.height(), std::vector<unsigned char>(image.pixelCount() * 4)};
    for (std::size_t i = 0; i < image.pixelCount(); ++i) {
        glm::vec3 p = image.pixels()[i];
        bool finite = std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z);
        for (int c = 0; c < 3; ++c) {
            float v = finite ? linearToSrgb(std::clamp(p[c] * scale, 0.0f, 1.0f)) : (c == 1 ? 0.0f : 1.0f);
            out.texels[i * 4 + c] = static_cast<unsigned char>(std::lround(v * 255.0f));
        }
        out.texels[i * 4 + 3] = 255;
    }
    return out;
}

void writePng(const std::string& path, const Image& image, float exposure) { writePng(path, toSrgb8(image, exposure)); }

void writePng(const std::string& path, const Rgba8Image& image) {
    std::vector<unsigned char> bytes(std::size_t(image.width) * image.height * 3);
    for (std::size_t i = 0; i < bytes.size() / 3; ++i) {
        for (int c = 0; c < 3; ++c) bytes[i * 3 + c] = image.texels[i * 4 + c];
    }
    std::string tmp = path + ".tmp";
    if (!stbi_write_png(tmp.c_str(), image.width, image.height, 3, bytes.data(), image.width * 3)) {
        throw Error(path + ": cannot write PNG");
    }
    commitFile(tmp, path);
}

void writePfm(const std::string& path, const Image& image) {
    std::string tmp = path + ".tmp";
    {
        std::ofstream out(tmp, std::ios::binary);
        out << "PF\n" << image.width() << " " << image.height() << "\n-1.0\n";
        // PFM stores rows bottom to top.
        for (int y = image.height() - 1; y >= 0; --y) {
            out.write(reinterpret_cast<const char*>(&image.at(0, y)), sizeof(glm::vec3) * image.width());
        }
        if (!out) {
            throw Error(path + ": cannot write PFM");
        }
    }
    commitFile(tmp, path);
}

std::vector<std::string> exrLayers(const std::string& path) {
    requireFile(path);
    Imf::InputFile file(path.c_str());
    std::set<std::string> layers;
    const Imf::ChannelList& channels = file.header().channels();
    for (auto it = channels.begin(); it != channels.end(); ++it) {
        std::string name = it.name();
        auto dot = name.rfind('.');
        layers.insert(dot == std::string::npos ? "" : name.substr(0, dot));
    }
    return {layers.begin(), layers.end()};
}

namespace {

Image readExr(const std::string& path, const std::string& layer) {
    try {
        Imf::InputFile file(path.c_str());
        Imath::Box2i dw = file.header().dataWindow();
        const int w = dw.max.x - dw.min.x + 1;
        const int h = dw.max.y - dw.min.y + 1;
        Image image(w, h);
        const Imf::ChannelList& channels = file.header().channels();
        Imf::FrameBuffer fb;
        char* base = reinterpret_cast<char*>(image.pixels().data()) -
                     (static_cast<std::ptrdiff_t>(dw.min.y) * w + dw.min.x) * sizeof(glm::vec3);
        for (int c = 0; c < 3; ++c) {
            std::string name = channelName(layer, "RGB"[c]);
            // A luminance-only EXR ("Y") fills all three channels.
            if (!channels.findChannel(name) && channels.findChannel(channelName(layer, 'Y'))) {
                name = channelName(layer, 'Y');
            }
            if (!channels.findChannel(name)) {
                throw Error(path + ": EXR has no channel '" + name + "'");
            }
            fb.insert(name, Imf::Slice(Imf::FLOAT, base + c * sizeof(float), sizeof(glm::vec3),
                                       sizeof(glm::vec3) * w));
        }
        file.setFrameBuffer(fb);
        file.readPixels(dw.min.y, dw.max.y);
        return image;
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path + ": cannot read EXR: " + e.what());
    }
}

// 8-bit formats only: Radiance HDR goes to our own reader (stb's can hang on a truncated file).
Image readStb(const std::string& path) {
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 3);
    if (!data) {
        throw Error(path + ": cannot read image: " + stbi_failure_reason());
    }
    Image image(w, h);
    float* out = &image.pixels()[0].x;
    for (std::size_t i = 0; i < static_cast<std::size_t>(w) * h * 3; ++i) {
        out[i] = srgbToLinear(data[i] / 255.0f);
    }
    stbi_image_free(data);
    return image;
}

} // namespace

Image readImage(const std::string& path, const std::string& layer) {
    requireFile(path);
    // Radiance HDR by its extension or its magic line, so that stb never sees one (even cut short).
    const std::string ext = lowerExtension(path);
    Image image = ext == ".exr"                                 ? readExr(path, layer)
                  : ext == ".hdr" || isRadianceHdrFile(path) ? readRadianceHdr(path)
                                                                : readStb(path);
    if (std::size_t bad = image.countNonFinite()) {
        throw Error(path + ": " + std::to_string(bad) + " pixels are NaN or infinite");
    }
    return image;
}

Rgba8Image readRgba8(const std::string& path) {
    requireFile(path);
    if (isRadianceHdrFile(path)) {
        throw Error(path + ": a Radiance HDR image cannot be an 8-bit texture");
    }
    int w = 0, h = 0, n = 0;
    unsigned char* data = stbi_load(path.c_str(), &w, &h, &n, 4);
    if (!data) {
        throw Error(path + ": cannot read image: " + stbi_failure_reason());
    }
    Rgba8Image image{w, h, std::vector<unsigned char>(data, data + static_cast<std::size_t>(w) * h * 4)};
    stbi_image_free(data);
    return image;
}

} // namespace bl
