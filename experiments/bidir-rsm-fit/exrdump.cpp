// exrdump IN.exr OUT.bin: every channel of an EXR as float32 planes after a header line "W H N" and
// the N channel names, for blocks.py (the project writes EXR; python here has no EXR reader).
#include <ImfInputFile.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <vector>
#include <string>
#include <cstdio>
int main(int argc, char** argv) {
    Imf::InputFile f(argv[1]);
    auto dw = f.header().dataWindow();
    int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
    std::vector<std::string> names;
    for (auto it = f.header().channels().begin(); it != f.header().channels().end(); ++it) names.push_back(it.name());
    std::vector<std::vector<float>> data(names.size(), std::vector<float>(size_t(w) * h));
    Imf::FrameBuffer fb;
    for (size_t i = 0; i < names.size(); ++i)
        fb.insert(names[i], Imf::Slice(Imf::FLOAT, (char*)(data[i].data() - dw.min.x - dw.min.y * w), sizeof(float), sizeof(float) * w));
    f.setFrameBuffer(fb);
    f.readPixels(dw.min.y, dw.max.y);
    FILE* o = fopen(argv[2], "wb");
    fprintf(o, "%d %d %zu\n", w, h, names.size());
    for (auto& n : names) fprintf(o, "%s\n", n.c_str());
    for (auto& d : data) fwrite(d.data(), 4, d.size(), o);
    fclose(o);
}
