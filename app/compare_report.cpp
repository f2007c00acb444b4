// Parsing of compare's own options, the reference cache key, and report.json / report.md.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "app/compare.h"
#include "app/render_overrides.h"
#include "integrators/integrator.h"
#include "lights/light_selection.h"

namespace lumis {

namespace {

/// FNV-1a 64 of data[0, n), continuing from `h` (the hash of the bytes before them; by default none).
uint64_t fnv1a(const unsigned char* data, size_t n, uint64_t h = 0xcbf29ce484222325ull) {
  for (size_t i = 0; i < n; ++i) h = (h ^ data[i]) * 0x100000001b3ull;
  return h;
}

std::string hex16(uint64_t h) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

std::vector<std::string> split(const std::string& text, char sep) {
  std::vector<std::string> parts;
  std::string cur;
  for (char c : text) {
    if (c == sep) {
      parts.push_back(cur);
      cur.clear();
    } else if (c != ' ') {
      cur += c;
    }
  }
  parts.push_back(cur);
  return parts;
}

std::string fmt(const char* f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}


bool has_variant(const CompareReport& r, const std::string& name) {
  for (const VariantResult& v : r.variants)
    if (v.name == name) return true;
  return false;
}

// Everything that determines the images: the comparison's settings, options that only one variant reads when that
// variant is compared, and where the reference comes from.
nlohmann::json settings_json(const CompareReport& r) {
  const RenderSettings& s = r.settings;
  nlohmann::json j = {{"width", r.width}, {"height", r.height}, {"mode", r.equal_time ? "equal-time" : "equal-spp"}};
  if (r.equal_time) j["time_budget"] = r.time_budget;
  else j["spp"] = r.spp;
  j["integrators"] = nlohmann::json::array();
  for (const VariantResult& v : r.variants) j["integrators"].push_back(v.name);
  j["max_depth"] = s.max_depth;
  j["rr_depth"] = s.rr_depth;
  j["sampler"] = sampler_type_name(s.sampler);
  j["seed"] = s.seed;
  j["light_selection"] = light_selection_name(s.light_selection);
  j["mis_heuristic"] = mis_heuristic_name(s.mis_heuristic);
  if (has_variant(r, "mis")) j["mis_light_probability"] = s.mis_light_probability;
  if (has_variant(r, "uniform")) j["uniform_measure"] = uniform_measure_name(s.uniform_measure);
  if (!r.camera.empty()) j["camera"] = r.camera;
  j["threads"] = s.threads;
  j["exposure"] = s.exposure;
  if (r.reference_spp) j["reference_spp"] = r.reference_spp;
  else j["reference_file"] = r.reference_source;
  return j;
}

}  // namespace

std::string settings_summary(const CompareReport& r) {
  const RenderSettings& s = r.settings;
  std::ostringstream out;
  if (!r.camera.empty()) out << "camera " << r.camera << ", ";
  out << "max depth " << s.max_depth << ", ";
  if (s.rr_depth > 0) out << "Russian roulette from depth " << s.rr_depth;
  else out << "no Russian roulette";
  out << ", " << sampler_type_name(s.sampler) << " sampler, seed " << s.seed << ", "
      << light_selection_name(s.light_selection) << " light selection, " << mis_heuristic_name(s.mis_heuristic)
      << " MIS heuristic";
  if (has_variant(r, "mis")) out << ", mis light probability " << fmt("%g", s.mis_light_probability);
  if (has_variant(r, "uniform")) out << ", uniform measure " << uniform_measure_name(s.uniform_measure);
  // The thread count changes the images only at equal time (how many samples fit); the exposure only the PNGs.
  if (r.equal_time && s.threads > 0) out << ", " << s.threads << (s.threads == 1 ? " thread" : " threads");
  if (r.equal_time && s.threads <= 0) out << ", all cores";
  if (s.exposure != 0) out << ", exposure " << fmt("%g", s.exposure);
  return out.str();
}

CropRect parse_crop(const std::string& text, int width, int height) {
  const std::vector<std::string> parts = split(text, ',');
  if (parts.size() != 4) throw std::invalid_argument("--crop: expected x,y,w,h, got '" + text + "'");
  int v[4];
  for (int i = 0; i < 4; ++i) {
    size_t used = 0;
    try {
      v[i] = std::stoi(parts[i], &used);
    } catch (const std::out_of_range&) {  // an integer all the same: not "not an integer"
      throw std::invalid_argument("--crop: '" + parts[i] + "' is out of range (expected x,y,w,h inside the image)");
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != parts[i].size())
      throw std::invalid_argument("--crop: '" + parts[i] + "' is not an integer (expected x,y,w,h)");
  }
  const CropRect c{v[0], v[1], v[2], v[3]};
  if (c.w <= 0 || c.h <= 0)
    throw std::invalid_argument("--crop: " + text + ": the width and height must be at least 1 pixel");
  if (c.x < 0 || c.y < 0 || c.w <= 0 || c.h <= 0 || c.w > width - c.x || c.h > height - c.y)
    throw std::invalid_argument("--crop: " + text + " is not inside the " + std::to_string(width) + "x" +
                                std::to_string(height) + " image");
  return c;
}

std::vector<std::string> parse_integrator_list(const std::string& text) {
  std::vector<std::string> names;
  std::set<std::string> seen;
  std::string valid;
  for (const std::string& n : integrator_names()) valid += (valid.empty() ? "" : ", ") + n;
  for (const std::string& n : split(text, ',')) {
    if (n.empty()) throw std::invalid_argument("--integrators: '" + text + "' has an empty entry (expected names "
                                               "separated by commas: " + valid + ")");
    bool known = false;
    for (const std::string& k : integrator_names()) known |= k == n;
    if (!known) throw std::invalid_argument("--integrators: unknown integrator '" + n + "' (valid: " + valid + ")");
    if (!seen.insert(n).second) throw std::invalid_argument("--integrators: '" + n + "' is listed twice");
    names.push_back(n);
  }
  return names;
}

std::string fnv1a_hex(const std::string& bytes, const std::string& after) {
  uint64_t h = fnv1a(nullptr, 0);
  if (!after.empty()) {
    if (after.size() != 16 || after.find_first_not_of("0123456789abcdef") != std::string::npos)
      throw std::invalid_argument("fnv1a_hex: '" + after + "' is not a hash");
    h = std::stoull(after, nullptr, 16);
  }
  return hex16(fnv1a(reinterpret_cast<const unsigned char*>(bytes.data()), bytes.size(), h));
}

std::string fnv1a_file_hex(const std::string& path) {
  uint64_t h = fnv1a(nullptr, 0);
  if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
    std::vector<unsigned char> piece(size_t{1} << 20);
    size_t n;
    while ((n = std::fread(piece.data(), 1, piece.size(), f)) > 0) h = fnv1a(piece.data(), n, h);
    std::fclose(f);
  }
  return hex16(h);
}

uint32_t reference_seed(uint32_t seed) { return seed ^ 0x9e3779b9u; }

double shared_error_scale(const std::vector<std::vector<float>>& maps) {
  double scale = 0;
  for (std::vector<float> m : maps) {
    m.erase(std::remove_if(m.begin(), m.end(), [](float v) { return !std::isfinite(v); }), m.end());
    if (m.empty()) continue;
    const size_t k = std::min(m.size() - 1, static_cast<size_t>(0.995 * static_cast<double>(m.size())));
    std::nth_element(m.begin(), m.begin() + static_cast<std::ptrdiff_t>(k), m.end());
    scale = std::max(scale, static_cast<double>(m[k]));
  }
  return scale > 0 ? scale : 1e-6;
}

nlohmann::json reference_key(const RenderSettings& s, uint32_t reference_spp) {
  // Everything the nee_mis reference image depends on besides the scene file (threads and time do not matter:
  // images are identical for any thread count, and the reference has no time budget).
  return {{"format", 1},
          {"integrator", "nee_mis"},
          {"spp", reference_spp},
          {"width", s.width},
          {"height", s.height},
          {"max_depth", s.max_depth},
          {"rr_depth", s.rr_depth},
          {"sampler", sampler_type_name(s.sampler)},
          {"seed", reference_seed(s.seed)},
          {"light_selection", light_selection_name(s.light_selection)},
          {"mis_heuristic", mis_heuristic_name(s.mis_heuristic)}};
}

std::string reference_hash(const std::string& scene_file_hash, const std::string& then, const RenderSettings& s,
                           uint32_t reference_spp) {
  return fnv1a_hex(then + "\n--lumis reference key--\n" + reference_key(s, reference_spp).dump(), scene_file_hash);
}

nlohmann::json report_json(const CompareReport& r) {
  nlohmann::json j;
  j["scene"] = r.scene;
  j["width"] = r.width;
  j["height"] = r.height;
  j["mode"] = r.equal_time ? "equal-time" : "equal-spp";
  if (r.equal_time) j["time_budget"] = r.time_budget;
  else j["spp"] = r.spp;
  j["settings"] = settings_json(r);
  j["reference"] = {{"source", r.reference_source}, {"png", r.reference_png}};
  if (r.reference_spp) {  // a rendered or cached reference; a given one has neither
    j["reference"]["spp"] = r.reference_spp;
    j["reference"]["hash"] = r.reference_hash;
  } else {  // a given one may be grey, as lumis diff says in its "channels"
    j["reference"]["channels"] = r.reference_grey ? "Y (as R, G, B)" : "R G B";
  }
  j["error_scale"] = r.error_scale;
  j["montage"] = r.montage;
  if (r.crop) j["crop"] = {r.crop->x, r.crop->y, r.crop->w, r.crop->h};
  if (!r.convergence_png.empty()) j["convergence_png"] = r.convergence_png;
  j["variants"] = nlohmann::json::array();
  for (const VariantResult& v : r.variants) {
    nlohmann::json jv = {{"name", v.name},
                         {"spp", v.spp},
                         {"seconds", v.seconds},
                         {"samples", v.samples},
                         {"rays", v.rays},
                         {"samples_per_second", v.samples_per_second()},
                         {"rays_per_second", v.rays_per_second()},
                         {"mse", v.mse},
                         {"relmse", v.rel_mse},
                         {"mae", v.mae},
                         {"efficiency", v.efficiency()},
                         {"exr", v.exr},
                         {"png", v.png},
                         {"error_png", v.error_png}};
    if (!v.convergence.empty()) {
      jv["convergence"] = nlohmann::json::array();
      for (const ConvergencePoint& p : v.convergence)
        jv["convergence"].push_back({{"spp", p.spp}, {"seconds", p.seconds}, {"mse", p.mse}, {"relmse", p.rel_mse}});
    }
    j["variants"].push_back(jv);
  }
  return j;
}

std::string report_markdown(const CompareReport& r) {
  std::ostringstream md;
  md << "# lumis compare: " << r.scene << "\n\n";
  md << r.width << "x" << r.height << ", ";
  if (r.equal_time) md << "equal time (" << fmt("%g", r.time_budget) << " s per variant)";
  else md << "equal samples (" << r.spp << " spp)";
  md << "; reference: " << r.reference_source;
  if (r.reference_spp) md << " (nee_mis, " << r.reference_spp << " spp)";
  if (r.reference_grey) md << " (grey: its Y is used as R, G and B)";
  md << ".\n\nSettings: " << settings_summary(r) << ".\n\n";
  md << "| variant | spp | time (s) | samples/s | rays/s | MSE | relMSE | efficiency |\n";
  md << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const VariantResult& v : r.variants)
    md << "| " << v.name << " | " << v.spp << " | " << fmt("%.3f", v.seconds) << " | "
       << fmt("%.3g", v.samples_per_second()) << " | " << fmt("%.3g", v.rays_per_second()) << " | "
       << fmt("%.4g", v.mse) << " | " << fmt("%.4g", v.rel_mse) << " | " << fmt("%.4g", v.efficiency()) << " |\n";
  md << "\nefficiency = 1 / (relMSE x time); relMSE = mean of (x - ref)^2 / (ref^2 + 0.01) over pixels and R, G, B.\n";
  md << "\n![montage](" << r.montage << ")\n";
  if (!r.convergence_png.empty()) md << "\n![convergence](" << r.convergence_png << ")\n";
  return md.str();
}

}  // namespace lumis
