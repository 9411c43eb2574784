// closed, eroded, flood, outline and boundary_length over byte masks.
#include "pipeline/bench/masks.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

namespace pleinair {

namespace OIIO = OIIO_NAMESPACE;

namespace {

// The mask in an image padded by r each way with `pad` (0 or 1), so a square of side 2r + 1
// never reaches past the buffer; and the mask's own pixels back out of such an image.
OIIO::ImageBuf padded(const Mask& m, int w, int h, int r, float pad) {
    OIIO::ImageBuf out(OIIO::ImageSpec(w + 2 * r, h + 2 * r, 1, OIIO::TypeDesc::UINT8));
    const float fill[] = {pad};
    OIIO::ImageBufAlgo::fill(out, fill);
    out.set_pixels(OIIO::ROI(r, r + w, r, r + h, 0, 1, 0, 1), OIIO::TypeDesc::UINT8, m.data());
    return out;
}

Mask unpadded(const OIIO::ImageBuf& b, int w, int h, int r) {
    Mask out(static_cast<size_t>(w) * h);
    b.get_pixels(OIIO::ROI(r, r + w, r, r + h, 0, 1, 0, 1), OIIO::TypeDesc::UINT8, out.data());
    return out;
}

}  // namespace

Mask closed(const Mask& m, int w, int h, int r) {
    if (r <= 0) return m;
    const int k = 2 * r + 1;
    return unpadded(
        OIIO::ImageBufAlgo::erode(OIIO::ImageBufAlgo::dilate(padded(m, w, h, r, 0.0f), k, k), k, k),
        w, h, r);
}

Mask eroded(const Mask& m, int w, int h, int r) {
    if (r <= 0) return m;
    const int k = 2 * r + 1;
    // Padded with ones, so only the shape's own edge erodes it. A square's erosion is a row's
    // then a column's: 2k reads a pixel instead of k^2.
    const OIIO::ImageBuf b = padded(m, w, h, r, 1.0f);
    return unpadded(OIIO::ImageBufAlgo::erode(OIIO::ImageBufAlgo::erode(b, k, 1), 1, k), w, h, r);
}

size_t flood(const Mask& m, int w, int h, size_t start, uint8_t value, std::vector<bool>& seen) {
    std::vector<size_t> todo{start};
    seen[start] = true;
    size_t n = 0;
    while (!todo.empty()) {
        const size_t i = todo.back();
        todo.pop_back();
        ++n;
        const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int nx = x + dx, ny = y + dy;
                if (nx < 0 || ny < 0 || nx >= w || ny >= h) continue;
                const size_t j = static_cast<size_t>(ny) * w + nx;
                if (seen[j] || (m[j] != 0) != (value != 0)) continue;
                seen[j] = true;
                todo.push_back(j);
            }
    }
    return n;
}

Mask outline(const Mask& m, int w, int h, int r) {
    Mask shut = closed(m, w, h, r);
    std::vector<bool> outside(shut.size(), false);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = static_cast<size_t>(y) * w + x;
            const bool edge = x == 0 || y == 0 || x == w - 1 || y == h - 1;
            if (edge && !shut[i] && !outside[i]) flood(shut, w, h, i, 0, outside);
        }
    for (size_t i = 0; i < shut.size(); ++i) shut[i] = !outside[i];
    return shut;
}

size_t boundary_length(const Mask& m, int w, int h) {
    // A side on the frame's edge is where the frame cuts the shape, not its edge.
    auto out = [&](int x, int y) {
        return x >= 0 && y >= 0 && x < w && y < h && m[static_cast<size_t>(y) * w + x] == 0;
    };
    size_t n = 0;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x)
            if (m[static_cast<size_t>(y) * w + x])
                n += out(x - 1, y) + out(x + 1, y) + out(x, y - 1) + out(x, y + 1);
    return n;
}

}  // namespace pleinair
