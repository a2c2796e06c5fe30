// analytic.cpp — exact ray / primitive intersections (see analytic.h).
//
// Every shape is solved in a shifted ray parameter s: the ray is first
// written as p(s) = p0 + s·D with D = d/|d| and p0 the point of the ray
// closest to the origin (the primitive's centre). The coefficients of the
// quadratics and the quartic then stay of the size of the primitive (≈ 1)
// however far away the camera is, which keeps the roots accurate; the
// caller's t is (t_c + s)/|d|.
#include "reference/analytic.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace ref {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kTorusR = 0.35;  // major radius (docs/meshes.md)
constexpr double kTorusT = 0.15;  // tube radius

// The ray in shifted form plus the s-interval that corresponds to [t_min, t_max].
struct ShiftedRay {
    glm::dvec3 p0{0.0}, D{0.0};
    double t_c = 0.0, len = 1.0;
    double s_min = 0.0, s_max = 0.0;
    double t_of(double s) const { return (t_c + s) / len; }
};

bool shift(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max, ShiftedRay* r) {
    r->len = glm::length(d);
    if (!(r->len > 0.0) || !std::isfinite(r->len)) return false;
    r->D = d / r->len;
    r->t_c = -glm::dot(o, r->D);
    r->p0 = o + r->t_c * r->D;
    r->s_min = t_min * r->len - r->t_c;
    r->s_max = t_max * r->len - r->t_c;
    return r->s_min <= r->s_max;
}

// u around +Y (docs/meshes.md: u = 0 and 1 at −Z, 0.5 at +Z, growing counter-clockwise
// seen from above) and the tangent along +u at a point off the axis.
double longitude_u(const glm::dvec3& p) {
    const double u = std::atan2(p.x, p.z) / (2.0 * kPi) + 0.5;
    return std::clamp(u, 0.0, 1.0);
}
glm::dvec3 longitude_tangent(const glm::dvec3& p) {
    const double rho = std::hypot(p.x, p.z);
    return rho > 0.0 ? glm::dvec3(p.z / rho, 0.0, -p.x / rho) : glm::dvec3(1.0, 0.0, 0.0);
}

// The candidate hit at parameter s: accepted when inside the s-interval and facing the ray.
// Keeps the nearest accepted one in *best.
struct Nearest {
    const ShiftedRay& ray;
    int facing;
    bool found = false;
    double s = std::numeric_limits<double>::infinity();
    ShapeHit hit;

    bool wants(double cand) const { return cand >= ray.s_min && cand <= ray.s_max && cand < s; }
    void offer(double cand, const glm::dvec3& normal, const glm::dvec2& uv, const glm::dvec3& tangent, int part) {
        if (!wants(cand)) return;
        if (!(facing * glm::dot(ray.D, normal) < 0.0)) return;  // back side (or edge-on)
        found = true;
        s = cand;
        hit.t = ray.t_of(cand);
        hit.position = ray.p0 + cand * ray.D;
        hit.normal = normal;
        hit.uv = uv;
        hit.tangent = tangent;
        hit.part = part;
    }
    bool finish(ShapeHit* out) const {
        if (found && out) *out = hit;
        return found;
    }
};

// Real roots of A·s² + 2B·s + C = 0 without cancellation; returns how many (0 … 2), ascending.
int quadratic(double A, double B, double C, double* roots) {
    if (A == 0.0) {
        if (B == 0.0) return 0;
        roots[0] = -C / (2.0 * B);
        return 1;
    }
    const double disc = B * B - A * C;
    if (disc < 0.0) return 0;
    const double q = -(B + std::copysign(std::sqrt(disc), B));
    if (q == 0.0) {  // B = 0 and disc = 0: a double root at 0
        roots[0] = 0.0;
        return 1;
    }
    double r0 = q / A, r1 = C / q;
    if (r0 > r1) std::swap(r0, r1);
    roots[0] = r0;
    roots[1] = r1;
    return 2;
}

// A flat disc cap of radius 0.5 at height y with normal ±Y.
void offer_cap(Nearest& best, const ShiftedRay& r, double y, bool top) {
    if (r.D.y == 0.0) return;
    const double s = (y - r.p0.y) / r.D.y;
    if (!best.wants(s)) return;
    const glm::dvec3 p = r.p0 + s * r.D;
    if (p.x * p.x + p.z * p.z > 0.25) return;
    // Planar UVs, upright seen from outside (top like the plane, bottom seen from below).
    const glm::dvec2 uv(0.5 + p.x, top ? 0.5 + p.z : 0.5 - p.z);
    best.offer(s, glm::dvec3(0.0, top ? 1.0 : -1.0, 0.0), uv, glm::dvec3(1.0, 0.0, 0.0), top ? 1 : 2);
}

double eval(const double* c, int n, double x) {
    double v = c[n];
    for (int i = n - 1; i >= 0; --i) v = v * x + c[i];
    return v;
}

}  // namespace

Shape analytic_shape(const std::string& name) {
    if (name == "sphere" || name == "icosphere") return Shape::Sphere;
    if (name == "cylinder") return Shape::Cylinder;
    if (name == "cone") return Shape::Cone;
    if (name == "torus") return Shape::Torus;
    return Shape::None;
}

int polynomial_roots(const double* c, int n, double lo, double hi, double* roots) {
    if (!(lo <= hi) || n < 1) return 0;
    if (n == 1) {
        const double x = -c[0] / c[1];
        if (x >= lo && x <= hi) {
            roots[0] = x;
            return 1;
        }
        return 0;
    }
    // Split [lo, hi] at the roots of the derivative: p is monotonic in between.
    double dc[4];
    for (int i = 1; i <= n; ++i) dc[i - 1] = i * c[i];
    double crit[4];
    const int nc = polynomial_roots(dc, n - 1, lo, hi, crit);
    double ends[6];
    int ne = 0;
    ends[ne++] = lo;
    for (int i = 0; i < nc; ++i)
        if (crit[i] > ends[ne - 1]) ends[ne++] = crit[i];
    if (hi > ends[ne - 1]) ends[ne++] = hi;

    int count = 0;
    auto add = [&](double x) {
        if (count == 0 || x > roots[count - 1]) roots[count++] = x;
    };
    for (int k = 0; k + 1 < ne; ++k) {
        double a = ends[k], b = ends[k + 1];
        double fa = eval(c, n, a), fb = eval(c, n, b);
        if (fa == 0.0) {
            add(a);  // also a double root sitting exactly on a derivative root (a grazing ray)
            continue;
        }
        if (fb == 0.0 || (fa < 0.0) == (fb < 0.0)) continue;  // fb == 0: added as the next a
        // Bisection: one root in (a, b), to the last bit.
        for (int it = 0; it < 200; ++it) {
            const double m = 0.5 * (a + b);
            if (!(m > a && m < b)) break;
            const double fm = eval(c, n, m);
            if (fm == 0.0) {
                a = b = m;
                break;
            }
            if ((fm < 0.0) == (fa < 0.0)) {
                a = m;
                fa = fm;
            } else {
                b = m;
            }
        }
        add(std::abs(eval(c, n, a)) <= std::abs(eval(c, n, b)) ? a : b);
    }
    if (ne >= 1 && eval(c, n, ends[ne - 1]) == 0.0) add(ends[ne - 1]);
    return count;
}

bool intersect_sphere(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max, int facing,
                      ShapeHit* hit) {
    ShiftedRay r;
    if (!shift(o, d, t_min, t_max, &r)) return false;
    const double h2 = 0.25 - glm::dot(r.p0, r.p0);  // (half chord)²
    if (h2 < 0.0) return false;
    const double h = std::sqrt(h2);
    Nearest best{r, facing};
    for (double s : {-h, h}) {
        if (!best.wants(s)) continue;
        const glm::dvec3 p = r.p0 + s * r.D;
        const glm::dvec3 n = glm::normalize(p);
        const double v = std::acos(std::clamp(n.y, -1.0, 1.0)) / kPi;  // 0 at the north pole
        best.offer(s, n, glm::dvec2(longitude_u(p), v), longitude_tangent(p), 0);
    }
    return best.finish(hit);
}

bool intersect_cylinder(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max, int facing,
                        ShapeHit* hit) {
    ShiftedRay r;
    if (!shift(o, d, t_min, t_max, &r)) return false;
    if (glm::dot(r.p0, r.p0) > 0.5 + 1e-12) return false;  // outside the bounding sphere (radius √0.5)
    Nearest best{r, facing};
    // Side: x² + z² = 0.25 for |y| ≤ 0.5.
    const double A = r.D.x * r.D.x + r.D.z * r.D.z;
    const double B = r.p0.x * r.D.x + r.p0.z * r.D.z;
    const double C = r.p0.x * r.p0.x + r.p0.z * r.p0.z - 0.25;
    double s[2];
    const int n = A > 0.0 ? quadratic(A, B, C, s) : 0;
    for (int i = 0; i < n; ++i) {
        const glm::dvec3 p = r.p0 + s[i] * r.D;
        if (std::abs(p.y) > 0.5) continue;
        const glm::dvec3 normal = glm::normalize(glm::dvec3(p.x, 0.0, p.z));
        best.offer(s[i], normal, glm::dvec2(longitude_u(p), 0.5 - p.y), longitude_tangent(p), 0);
    }
    offer_cap(best, r, 0.5, true);
    offer_cap(best, r, -0.5, false);
    return best.finish(hit);
}

bool intersect_cone(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max, int facing,
                    ShapeHit* hit) {
    ShiftedRay r;
    if (!shift(o, d, t_min, t_max, &r)) return false;
    if (glm::dot(r.p0, r.p0) > 0.5 + 1e-12) return false;
    Nearest best{r, facing};
    // Side: x² + z² = (w/2)² with w = 0.5 − y ∈ [0, 1] (radius 0 at the apex, 0.5 at the base).
    const double w0 = 0.5 - r.p0.y, wd = -r.D.y;  // w(s) = w0 + s·wd
    const double A = r.D.x * r.D.x + r.D.z * r.D.z - 0.25 * wd * wd;
    const double B = r.p0.x * r.D.x + r.p0.z * r.D.z - 0.25 * w0 * wd;
    const double C = r.p0.x * r.p0.x + r.p0.z * r.p0.z - 0.25 * w0 * w0;
    double s[2];
    const int n = quadratic(A, B, C, s);
    for (int i = 0; i < n; ++i) {
        const glm::dvec3 p = r.p0 + s[i] * r.D;
        const double w = 0.5 - p.y;
        if (w < 0.0 || w > 1.0) continue;  // the other nappe of the double cone, or below the base
        // Outward normal: the gradient of x² + z² − w²/4, i.e. (2x, w/2, 2z) — horizontal
        // part ∝ radius, vertical part = radius/2 (docs/meshes.md: normalize(sin φ, 0.5, cos φ)).
        glm::dvec3 normal(2.0 * p.x, 0.5 * w, 2.0 * p.z);
        normal = glm::length(normal) > 0.0 ? glm::normalize(normal) : glm::dvec3(0.0, 1.0, 0.0);
        best.offer(s[i], normal, glm::dvec2(longitude_u(p), w), longitude_tangent(p), 0);
    }
    offer_cap(best, r, -0.5, false);
    return best.finish(hit);
}

bool intersect_torus(const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max, int facing,
                     ShapeHit* hit) {
    ShiftedRay r;
    if (!shift(o, d, t_min, t_max, &r)) return false;
    const double R = kTorusR, T = kTorusT, bound = R + T;
    const double g2 = glm::dot(r.p0, r.p0);
    if (g2 > bound * bound) return false;  // misses the bounding sphere
    const double h = std::sqrt(bound * bound - g2);
    // (|p|² + R² − T²)² − 4R²(x² + z²) = 0 with p = p0 + s·D, |D| = 1, and
    // a = p0·D (≈ 0 by construction), k = |p0|² + R² − T², e = Dxz·Dxz, f = p0xz·Dxz, g = |p0xz|².
    const double a = glm::dot(r.p0, r.D);
    const double k = g2 + R * R - T * T;
    const double e = r.D.x * r.D.x + r.D.z * r.D.z;
    const double f = r.p0.x * r.D.x + r.p0.z * r.D.z;
    const double g = r.p0.x * r.p0.x + r.p0.z * r.p0.z;
    const double c[5] = {k * k - 4.0 * R * R * g, 4.0 * a * k - 8.0 * R * R * f, 4.0 * a * a + 2.0 * k - 4.0 * R * R * e,
                         4.0 * a, 1.0};
    const double pad = 1e-9;
    const double lo = std::max(r.s_min, -h - pad), hi = std::min(r.s_max, h + pad);
    double roots[4];
    const int n = polynomial_roots(c, 4, lo, hi, roots);
    Nearest best{r, facing};
    for (int i = 0; i < n; ++i) {
        const glm::dvec3 p = r.p0 + roots[i] * r.D;
        const double rho = std::hypot(p.x, p.z);
        if (!(rho > 0.0)) continue;  // the axis is inside the hole (R > T): never on the surface
        // Outward normal: from the tube's centre circle to the point.
        const glm::dvec3 centre(R * p.x / rho, 0.0, R * p.z / rho);
        const glm::dvec3 normal = glm::normalize(p - centre);
        // v around the tube: 0 at the top, 0.25 outside, 0.5 at the bottom, 0.75 inside.
        double v = (0.5 * kPi - std::atan2(p.y, rho - R)) / (2.0 * kPi);
        v -= std::floor(v);
        best.offer(roots[i], normal, glm::dvec2(longitude_u(p), v), longitude_tangent(p), 0);
        if (best.found) break;  // roots are ascending: the first facing one is the nearest
    }
    return best.finish(hit);
}

bool intersect_shape(Shape shape, const glm::dvec3& o, const glm::dvec3& d, double t_min, double t_max, int facing,
                     ShapeHit* hit) {
    switch (shape) {
        case Shape::Sphere: return intersect_sphere(o, d, t_min, t_max, facing, hit);
        case Shape::Cylinder: return intersect_cylinder(o, d, t_min, t_max, facing, hit);
        case Shape::Cone: return intersect_cone(o, d, t_min, t_max, facing, hit);
        case Shape::Torus: return intersect_torus(o, d, t_min, t_max, facing, hit);
        case Shape::None: break;
    }
    return false;
}

}  // namespace ref
