// `lumis warptest`: a table from name to (sampling routine, density), checked by check_warp (app/warp_check.cpp).
// To add a warp, add one row to registry(): its sampler returns a direction (nullopt when it fails) and its pdf is
// the solid-angle density in the same frame.
#include "app/warptest.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <iomanip>
#include <optional>
#include <sstream>

#include "core/file_ext.h"
#include "core/warp.h"

namespace lumis {

namespace {

struct WarpEntry {
  const char* name;
  const char* param_help;  ///< what `param` means, or nullptr when unused
  float default_param;
  std::function<Warp(float)> make;
  float param_lo = 0, param_hi = 0;  ///< the open interval (lo, hi) `param` must lie in; hi is included if hi_closed
  bool hi_closed = false;
  /// For a lobe about the pole: the factor k >= 1 by which the cells' directions are stretched (nullptr: none).
  std::function<double(float)> stretch;
  /// Why the test cannot decide at this param, inside the domain though it is (empty when it can; nullptr: always).
  std::function<std::string(float)> undecidable;
};

// The cells are uniform in (cos theta, phi), so the top row reaches 0.32 rad from the pole. A GGX lobe much narrower
// than at the default alpha = 0.3 falls inside that row, where neither the histogram nor the pdf's integral over a
// cell (a near-delta between quadrature points) can tell a right sampler from a wrong one. Below alpha = 0.3 the
// cells are therefore laid out in directions stretched by k = 0.3 / alpha, where the lobe is as wide as at 0.3.
double ggx_stretch(float alpha) { return std::max(1.0, 0.3 / alpha); }
// D peaks at 1 / (pi alpha^2), beyond the float range below alpha = 3e-20 (1e-19 passes).
std::string ggx_undecidable(float alpha) {
  return alpha < 1e-19f ? "the density at the lobe's peak, 1 / (pi alpha^2), exceeds the float range; the test "
                          "decides for alpha from 1e-19"
                        : "";
}
// Likewise a cap narrower than the default's (cos_max 0.9) is stretched to a rim at cos theta = 0.875, mid-row: a
// rim on a row's edge would be sorted by rounding there.
double cap_stretch(float cos_max) {
  const auto tan_radius = [](double c) { return std::sqrt(1 - c * c) / c; };
  return cos_max > 0.9f ? tan_radius(0.875) / tan_radius(cos_max) : 1.0;
}
// Near the pole a float direction resolves cos theta to 6e-8, so the rim that spherical_cap_pdf sees moves by up to
// 3e-8 / (1 - cos_max) of the cap. Measured: cos_max 0.9999 passes with 1e8 samples, 0.99995 fails with 1e8 and
// 0.99999 with 1e6, exact sampler and pdf alike.
std::string cap_undecidable(float cos_max) {
  return cos_max > 0.9999f ? "float directions resolve cos theta only to 6e-8, too coarse at the rim of so small a "
                             "cap; the test decides for cos_max up to 0.9999"
                           : "";
}

// GGX visible normals are tested for a view direction 45 degrees off the normal, where the visible-normal density is
// clearly asymmetric.
const Vec3 kGgxWo{0.70710678f, 0.0f, 0.70710678f};

Warp ggx_warp(VndfMethod method, float alpha) {
  return {[=](Vec2 u) -> std::optional<Vec3> { return sample_ggx_vndf(kGgxWo, alpha, alpha, u, method); },
          [=](Vec3 wm) { return double(ggx_vndf_pdf(kGgxWo, wm, alpha, alpha)); }};
}

// A spherical triangle seen from the origin, above the horizon and off the pole, about 0.3 sr.
Warp spherical_triangle_warp() {
  const Vec3 a{-0.3f, -0.2f, 1.0f}, b{0.6f, -0.1f, 0.8f}, c{0.1f, 0.6f, 0.9f};
  const Vec3 o{0, 0, 0};
  const float omega = triangle_solid_angle(o, a, b, c);
  // Inside the triangle iff w is on the inner side of all three great circles through its edges.
  const Vec3 nab = cross(a, b), nbc = cross(b, c), nca = cross(c, a);
  const float orient = dot(nab, c) > 0 ? 1.0f : -1.0f;
  return {[=](Vec2 u) -> std::optional<Vec3> {
            const auto s = sample_spherical_triangle(o, a, b, c, u);
            if (!s) return std::nullopt;
            return s->w;
          },
          [=](Vec3 w) {
            const bool inside = orient * dot(nab, w) >= 0 && orient * dot(nbc, w) >= 0 && orient * dot(nca, w) >= 0;
            return inside ? 1.0 / omega : 0.0;
          }};
}

const std::vector<WarpEntry>& registry() {
  static const std::vector<WarpEntry> entries = {
      {"uniform_theta_phi", nullptr, 0,
       [](float) {
         return Warp{sample_uniform_theta_phi_hemisphere,
                     [](Vec3 w) { return double(uniform_theta_phi_hemisphere_pdf(w)); }};
       }},
      {"uniform_hemisphere", nullptr, 0,
       [](float) { return Warp{sample_uniform_hemisphere, [](Vec3 w) { return double(uniform_hemisphere_pdf(w)); }}; }},
      {"cosine_hemisphere", nullptr, 0,
       [](float) {
         return Warp{[](Vec2 u) -> std::optional<Vec3> { return sample_cosine_hemisphere(u); },
                     [](Vec3 w) { return double(cosine_hemisphere_pdf(w)); }};
       }},
      {"uniform_sphere", nullptr, 0,
       [](float) { return Warp{sample_uniform_sphere, [](Vec3) { return double(uniform_sphere_pdf()); }}; }},
      {"spherical_cap", "cos_max", 0.9f,
       [](float cos_max) {
         return Warp{[=](Vec2 u) -> std::optional<Vec3> { return sample_spherical_cap(u, cos_max); },
                     [=](Vec3 w) { return double(spherical_cap_pdf(w, cos_max)); }};
       },
       -1.0f, 1.0f, false, cap_stretch, cap_undecidable},
      {"ggx_heitz", "alpha", 0.3f, [](float alpha) { return ggx_warp(VndfMethod::Heitz2018, alpha); }, 0.0f, 1.0f,
       true, ggx_stretch, ggx_undecidable},
      {"ggx_cap", "alpha", 0.3f, [](float alpha) { return ggx_warp(VndfMethod::SphericalCap2023, alpha); }, 0.0f,
       1.0f, true, ggx_stretch, ggx_undecidable},
      {"spherical_triangle", nullptr, 0, [](float) { return spherical_triangle_warp(); }},
  };
  return entries;
}

}  // namespace

// The density gains the Jacobian of the inverse map, k^-2 / |(x / k, y / k, z)|^3 for a unit w. Bins in the stretched
// directions are bins in the original ones, finer near the pole: the test still compares the sampler with its pdf.
Warp stretched(const Warp& warp, double k) {
  auto map = [](Vec3 w, double kxy) {
    const double x = kxy * w.x, y = kxy * w.y, len = std::sqrt(x * x + y * y + double(w.z) * w.z);
    return std::pair{Vec3(float(x / len), float(y / len), float(w.z / len)), len};
  };
  return {[=](Vec2 u) -> std::optional<Vec3> {
            const std::optional<Vec3> w = warp.sample(u);
            return w ? std::optional<Vec3>(map(*w, k).first) : std::nullopt;
          },
          [=](Vec3 w) {
            const auto [original, len] = map(w, 1 / k);
            return warp.pdf(original) / (k * k * len * len * len);
          }};
}

std::vector<std::string> warptest_names() {
  std::vector<std::string> names;
  for (const WarpEntry& e : registry()) names.emplace_back(e.name);
  return names;
}

int run_warptest(const std::string& name, double given, uint64_t samples, const std::string& out_png,
                 std::ostream& out, std::ostream& err) {
  const auto& entries = registry();
  const auto it = std::find_if(entries.begin(), entries.end(), [&](const WarpEntry& e) { return name == e.name; });
  if (it == entries.end()) {
    if (name.empty()) err << "lumis: warptest: which warp? Valid names:";  // none given
    else err << "lumis: warptest: unknown warp '" << name << "'. Valid names:";
    for (const WarpEntry& e : entries) err << ' ' << e.name;
    err << '\n';
    return 2;
  }
  if (!std::isnan(given)) {
    if (!it->param_help) {
      err << "lumis: warptest: " << name << " takes no --param\n";
      return 2;
    }
    // Checked as given and as the 32-bit float the warp is computed in (0.99999999 rounds to 1, 1e-50 to 0).
    const auto inside = [&](double v) {
      return v > it->param_lo && (it->hi_closed ? v <= it->param_hi : v < it->param_hi);
    };
    if (!inside(given) || !inside(static_cast<float>(given))) {
      std::ostringstream found;  // enough digits to tell 1.0000001 from the bound 1
      found << std::setprecision(9) << given;
      if (inside(given)) found << ", which is " << static_cast<float>(given) << " as the 32-bit float it is used as";
      err << "lumis: warptest: --param: " << it->param_help << " of " << name << " must lie in (" << it->param_lo
          << ", " << it->param_hi << (it->hi_closed ? "]" : ")") << ", found " << found.str() << '\n';
      return 2;
    }
  }
  const float param = std::isnan(given) ? it->default_param : static_cast<float>(given);
  if (const std::string why = it->undecidable ? it->undecidable(param) : ""; !why.empty()) {
    err << "lumis: warptest: " << name << " with " << it->param_help << " = " << param
        << ": the test cannot decide: " << why << '\n';
    return 2;
  }
  if (!out_png.empty()) {  // checked before the work, like render's -o
    if (const std::string problem = image_output_problem(out_png, "warp.png"); !problem.empty()) {
      err << "lumis: warptest: " << out_png << ": " << problem << '\n';
      return 2;
    }
  }
  const double k = it->stretch ? it->stretch(param) : 1.0;
  const Warp warp = k > 1 ? stretched(it->make(param), k) : it->make(param);
  std::ostringstream title, cells_note;
  title << name;
  if (it->param_help) title << " (" << it->param_help << " = " << param << ")";
  if (k > 1) cells_note << " of directions stretched by " << k << " in x and y (so that the lobe spans the cells)";
  return check_warp(warp, title.str(), cells_note.str(), samples, out_png, out, err);
}

}  // namespace lumis
