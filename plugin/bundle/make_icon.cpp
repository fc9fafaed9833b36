// SPDX-License-Identifier: Apache-2.0
// Draws the plugin's icon and writes it as a PNG (build tool; no image library needed):
// a lit sphere on a dark rounded square, split along the diagonal into a noisy render (upper
// left) and its clean version (lower right), i.e. what the effect does.
// Usage: afn_ofx_icon OUT.png [SIZE]   (SIZE 16..1024, default 128)
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace {

uint32_t crc32(const uint8_t* p, size_t n, uint32_t crc = 0)
{
    static uint32_t table[256];
    static bool ready = false;
    if (!ready) {
        for (uint32_t i = 0; i < 256; ++i) {
            uint32_t c = i;
            for (int k = 0; k < 8; ++k)
                c = c & 1 ? 0xedb88320u ^ (c >> 1) : c >> 1;
            table[i] = c;
        }
        ready = true;
    }
    crc = ~crc;
    for (size_t i = 0; i < n; ++i)
        crc = table[(crc ^ p[i]) & 0xff] ^ (crc >> 8);
    return ~crc;
}

void put32(std::vector<uint8_t>& out, uint32_t v)
{
    for (int s = 24; s >= 0; s -= 8)
        out.push_back(uint8_t(v >> s));
}

void chunk(std::vector<uint8_t>& png, const char* type, const std::vector<uint8_t>& data)
{
    put32(png, uint32_t(data.size()));
    const size_t start = png.size();
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), data.begin(), data.end());
    put32(png, crc32(png.data() + start, png.size() - start));
}

/// RGBA8 rows as a PNG: zlib stream of stored (uncompressed) deflate blocks.
std::vector<uint8_t> encodePng(const std::vector<uint8_t>& rgba, int size)
{
    std::vector<uint8_t> raw;
    for (int y = 0; y < size; ++y) {
        raw.push_back(0); // filter: none
        raw.insert(raw.end(), rgba.begin() + size_t(y) * size * 4,
            rgba.begin() + size_t(y + 1) * size * 4);
    }
    std::vector<uint8_t> z = { 0x78, 0x01 };
    for (size_t pos = 0; pos < raw.size();) {
        const size_t n = std::min<size_t>(65535, raw.size() - pos);
        z.push_back(pos + n == raw.size() ? 1 : 0);
        z.push_back(uint8_t(n));
        z.push_back(uint8_t(n >> 8));
        z.push_back(uint8_t(~n));
        z.push_back(uint8_t(~n >> 8));
        z.insert(z.end(), raw.begin() + pos, raw.begin() + pos + n);
        pos += n;
    }
    uint32_t a = 1, b = 0; // Adler-32
    for (uint8_t v : raw) {
        a = (a + v) % 65521;
        b = (b + a) % 65521;
    }
    put32(z, (b << 16) | a);

    std::vector<uint8_t> png = { 0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n' };
    std::vector<uint8_t> ihdr;
    put32(ihdr, uint32_t(size));
    put32(ihdr, uint32_t(size));
    ihdr.insert(ihdr.end(), { 8, 6, 0, 0, 0 }); // 8-bit RGBA, deflate, no filter, no interlace
    chunk(png, "IHDR", ihdr);
    chunk(png, "IDAT", z);
    chunk(png, "IEND", {});
    return png;
}

float hashNoise(int x, int y)
{
    uint32_t h = uint32_t(x) * 73856093u ^ uint32_t(y) * 19349663u;
    h ^= h >> 13;
    h *= 0x5bd1e995u;
    h ^= h >> 15;
    return float(h & 0xffffu) / 65535.0f; // [0, 1]
}

/// Colour (linear-ish, 0..1) and coverage of the icon at (u, v) in [0, 1]^2, v down.
void shade(float u, float v, int px, int py, float rgb[3], float& alpha)
{
    // Rounded square: corner radius 0.16.
    const float r = 0.16f, dx = std::max(std::fabs(u - 0.5f) - (0.5f - r), 0.0f),
                dy = std::max(std::fabs(v - 0.5f) - (0.5f - r), 0.0f);
    alpha = dx * dx + dy * dy <= r * r ? 1.0f : 0.0f;
    const float bg = 0.13f + 0.08f * (1.0f - v);
    rgb[0] = bg * 0.85f;
    rgb[1] = bg * 0.95f;
    rgb[2] = bg * 1.25f;
    // Sphere of radius 0.34 at the centre, lit from the upper left, warm key and teal fill.
    const float sx = (u - 0.5f) / 0.34f, sy = (v - 0.5f) / 0.34f, d2 = sx * sx + sy * sy;
    if (d2 <= 1.0f) {
        const float nz = std::sqrt(1.0f - d2);
        const float key = std::max(0.0f, -0.55f * sx - 0.6f * sy + 0.58f * nz);
        const float fill = std::max(0.0f, 0.6f * sx + 0.3f * sy + 0.74f * nz);
        const float spec = std::pow(std::max(0.0f, -0.4f * sx - 0.45f * sy + 0.8f * nz), 40.0f);
        rgb[0] = 0.05f + 0.95f * key + 0.05f * fill + spec;
        rgb[1] = 0.04f + 0.55f * key + 0.35f * fill + spec;
        rgb[2] = 0.05f + 0.20f * key + 0.45f * fill + spec;
    }
    const float diagonal = u + v - 1.0f; // < 0: upper-left half
    if (diagonal < 0.0f) {
        // Monte Carlo noise: heavy per-pixel speckle and rare fireflies.
        const float n = hashNoise(px, py);
        const float gain = n > 0.985f ? 6.0f : 0.15f + 1.7f * hashNoise(py + 977, px + 31);
        for (int i = 0; i < 3; ++i)
            rgb[i] *= gain;
    }
    if (std::fabs(diagonal) < 0.012f)
        rgb[0] = rgb[1] = rgb[2] = 0.95f; // the split line
}

uint8_t toByte(float linear)
{
    const float c = std::min(std::max(linear, 0.0f), 1.0f);
    const float s = c <= 0.0031308f ? 12.92f * c : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f;
    return uint8_t(std::lround(s * 255.0f));
}

} // namespace

int main(int argc, char** argv)
{
    if (argc < 2 || argc > 3) {
        std::fprintf(stderr, "usage: %s OUT.png [SIZE]\n", argv[0]);
        return 2;
    }
    const int size = argc == 3 ? std::atoi(argv[2]) : 128;
    if (size < 16 || size > 1024) {
        std::fprintf(stderr, "afn_ofx_icon ERROR: size must be 16..1024\n");
        return 1;
    }
    // 4x4 supersampling for the edges; the noise stays per output pixel.
    const int ss = 4;
    std::vector<uint8_t> rgba(size_t(size) * size * 4);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            float acc[3] = { 0, 0, 0 }, cover = 0;
            for (int j = 0; j < ss; ++j)
                for (int i = 0; i < ss; ++i) {
                    float c[3], a;
                    shade((x + (i + 0.5f) / ss) / size, (y + (j + 0.5f) / ss) / size, x, y, c, a);
                    for (int k = 0; k < 3; ++k)
                        acc[k] += c[k] * a;
                    cover += a;
                }
            uint8_t* p = &rgba[(size_t(y) * size + x) * 4];
            for (int k = 0; k < 3; ++k)
                p[k] = toByte(cover > 0 ? acc[k] / cover : 0.0f);
            p[3] = uint8_t(std::lround(255.0f * cover / (ss * ss)));
        }
    const std::vector<uint8_t> png = encodePng(rgba, size);
    // Atomic: write beside the target, then rename over it.
    const std::string out = argv[1], tmp = out + ".tmp";
    FILE* f = std::fopen(tmp.c_str(), "wb");
    bool ok = f != nullptr;
    if (f) {
        ok = std::fwrite(png.data(), 1, png.size(), f) == png.size();
        ok = std::fclose(f) == 0 && ok;
    }
    if (!ok || std::rename(tmp.c_str(), out.c_str()) != 0) {
        std::fprintf(stderr, "afn_ofx_icon ERROR: cannot write %s\n", out.c_str());
        std::remove(tmp.c_str());
        return 1;
    }
    return 0;
}
