#include "viewer/render/Pattern.h"

#include <cmath>

#include "viewer/render/Color.h"

namespace viewer::render {

LinearTexture LinearTexture::fromSrgb(const Rgb8Image& image) {
    // A table: 256 decodes instead of one pow per channel of every texel.
    float table[256];
    for (int i = 0; i < 256; ++i) table[i] = float(srgbToLinear(i / 255.0));
    LinearTexture t;
    t.width = image.width;
    t.height = image.height;
    t.rgb.resize(image.pixels.size());
    for (size_t i = 0; i < image.pixels.size(); ++i) t.rgb[i] = table[image.pixels[i]];
    return t;
}

namespace {

// The coordinate plane most facing n: its two axes a, b in x, y, z order.
void facingAxes(const csg::Vec3& n, int& a, int& b) {
    const csg::Vec3 m = glm::abs(n);
    a = 0, b = 1;  // normal mostly z
    if (m.x >= m.y && m.x >= m.z)
        a = 1, b = 2;
    else if (m.y >= m.z)
        a = 0, b = 2;
}

}  // namespace

PlaneFrame planeFrame(const csg::Vec3& n) {
    // The facing plane's two axes projected onto the plane and made orthonormal (Gram-Schmidt),
    // which is the identity on an axis-aligned plane. Neither axis is parallel to n, because n
    // is mostly along the third.
    int a, b;
    facingAxes(n, a, b);
    csg::Vec3 ea(0.0), eb(0.0);
    ea[a] = 1.0;
    eb[b] = 1.0;
    const csg::Vec3 u = glm::normalize(ea - glm::dot(ea, n) * n);
    csg::Vec3 v = eb - glm::dot(eb, n) * n;
    v = glm::normalize(v - glm::dot(v, u) * u);
    return {u, v};
}

csg::Vec2 planarCoordinates(const csg::Vec3& p, const csg::Vec3& n, bool halfSpace) {
    if (halfSpace) {
        const PlaneFrame frame = planeFrame(n);
        return {glm::dot(p, frame.u), glm::dot(p, frame.v)};
    }
    int a, b;
    facingAxes(n, a, b);
    return {p[a], p[b]};
}

int checkerParity(const csg::Vec2& uv, double inverseScale) {
    const double i = std::floor(uv.x * inverseScale) + std::floor(uv.y * inverseScale);
    return int(i - 2.0 * std::floor(i * 0.5));  // i mod 2 for negative i too
}

csg::Vec3 sampleTexture(const LinearTexture& texture, const csg::Vec2& uv, double inverseScale) {
    // Texel coordinates with texel centres at integers + 0.5; v runs up, rows run down.
    const double s = uv.x * inverseScale, t = uv.y * inverseScale;
    const double x = (s - std::floor(s)) * texture.width - 0.5;
    const double y = (1.0 - (t - std::floor(t))) * texture.height - 0.5;
    const double x0 = std::floor(x), y0 = std::floor(y);
    const double fx = x - x0, fy = y - y0;
    // Wrapped neighbours: the texture tiles.
    auto wrap = [](double i, int size) {
        const int k = int(i) % size;
        return k < 0 ? k + size : k;
    };
    const int xs[2] = {wrap(x0, texture.width), wrap(x0 + 1.0, texture.width)};
    const int ys[2] = {wrap(y0, texture.height), wrap(y0 + 1.0, texture.height)};
    csg::Vec3 sum(0.0);
    for (int j = 0; j < 2; ++j) {
        for (int i = 0; i < 2; ++i) {
            const double w = (i ? fx : 1.0 - fx) * (j ? fy : 1.0 - fy);
            const float* texel = &texture.rgb[(size_t(ys[j]) * texture.width + xs[i]) * 3];
            sum += w * csg::Vec3(texel[0], texel[1], texel[2]);
        }
    }
    return sum;
}

}  // namespace viewer::render
