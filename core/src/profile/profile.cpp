// Profile JSON: write, read back exactly, digest the training data.
#include "tristim/profile/profile.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "tristim/error.hpp"
#include "tristim/io/limits.hpp"
#include "tristim/profile/export.hpp"
#include "tristim/profile/fields.hpp"
#include "tristim/version.hpp"

namespace tristim {

namespace {

struct Fnv1a64 {
  uint64_t h = 0xcbf29ce484222325ULL;
  void bytes(const void* data, size_t n) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) {
      h ^= p[i];
      h *= 0x100000001b3ULL;
    }
  }
  std::string text() const {
    char buf[40];
    std::snprintf(buf, sizeof buf, "fnv1a64:%016llx", static_cast<unsigned long long>(h));
    return buf;
  }
  void f64(double d) {
    uint64_t u;
    std::memcpy(&u, &d, 8);
    unsigned char le[8];
    for (int i = 0; i < 8; ++i) le[i] = static_cast<unsigned char>(u >> (8 * i));
    bytes(le, 8);
  }
};

Vec3 read_vec3(const json::Value& v, const std::string& what) {
  const auto a = v.as_numbers(what);
  if (a.size() != 3) throw Error(ErrorCode::ProfileInvalid, what + " must have 3 numbers");
  return Vec3(a[0], a[1], a[2]);
}

std::string guess_illuminant(const Vec3& w) {
  auto same = [&](const Vec3& ref) {
    return w[1] > 0 && ((w / w[1]) - (ref / ref[1])).cwiseAbs().maxCoeff() < 1e-4;
  };
  if (same(whites::D50())) return "D50";
  if (same(whites::D65())) return "D65";
  return "custom";
}


}  // namespace

std::string training_digest(const std::vector<std::string>& ids, const PatchMatrix& rgb, const PatchMatrix& xyz) {
  Fnv1a64 f;
  const char* tag = "tristim-training-v1\n";
  f.bytes(tag, std::strlen(tag));
  for (Eigen::Index i = 0; i < rgb.rows(); ++i) {
    const std::string id = i < static_cast<Eigen::Index>(ids.size()) ? ids[i] : std::to_string(i + 1);
    f.bytes(id.data(), id.size());
    f.bytes("", 1);
    for (int c = 0; c < 3; ++c) f.f64(rgb(i, c));
    for (int c = 0; c < 3; ++c) f.f64(xyz(i, c));
  }
  return f.text();
}

std::string bytes_digest(const std::string& bytes) {
  Fnv1a64 f;
  f.bytes(bytes.data(), bytes.size());
  return f.text();
}

json::Value summary_json(const Summary& s) { return fields::write(s); }

json::Value metrics_json(const Metrics& m, const std::vector<std::string>& ids, bool per_patch) {
  json::Value o = fields::write(m);
  if (per_patch) {
    json::Value p = json::Value::object();
    if (!ids.empty()) p.set("ids", fields::write(ids));
    fields::write_members(m.patches, p);
    o.set("patches", p);
  }
  return o;
}

Profile make_profile(const ModelEvaluation& ev, const FitOptions& options, const std::vector<std::string>& ids,
                     const PatchMatrix& rgb, const PatchMatrix& xyz, const std::string& white_patch,
                     const std::string& illuminant) {
  Profile p;
  p.tristim_version = kVersion;
  p.model = ev.fit.model;
  p.objective = ev.fit.objective;
  p.white = options.white;
  p.illuminant = illuminant.empty() ? guess_illuminant(options.white) : illuminant;
  p.white_preserved = ev.fit.white_preserved;
  p.white_patch = white_patch;
  p.white_RGB = options.white_RGB;
  p.white_XYZ = options.white_XYZ;
  p.training_patches = static_cast<int>(rgb.rows());
  p.training_digest = training_digest(ids, rgb, xyz);
  p.rgb_max = rgb.rows() > 0 ? rgb.maxCoeff() : 1.0;
  if (!(p.rgb_max > 0)) p.rgb_max = 1.0;
  p.status = ev.fit.status;
  p.message = ev.fit.message;
  p.condition_number = ev.fit.condition_number;
  p.iterations = ev.fit.iterations;
  p.objective_value = ev.fit.objective_value;
  p.metrics = json::Value::object();
  p.metrics.set("training", metrics_json(ev.training));
  if (ev.has_loo) p.metrics.set("loo", metrics_json(ev.loo));
  return p;
}

namespace {
/// training.camera_RGB / reference_XYZ: one row of 3 finite numbers per label.
PatchMatrix read_training_rows(const json::Value& v, const char* name, size_t n) {
  const auto& rows = v.as_array(name);
  if (rows.size() != n)
    throw Error(ErrorCode::ProfileInvalid, std::string(name) + ": " + std::to_string(rows.size()) + " rows for " +
                                               std::to_string(n) + " labels");
  PatchMatrix m(static_cast<Eigen::Index>(n), 3);
  for (size_t i = 0; i < n; ++i) {
    const auto r = rows[i].as_numbers(name);
    if (r.size() != 3) throw Error(ErrorCode::ProfileInvalid, std::string(name) + ": rows of 3 values");
    for (int c = 0; c < 3; ++c) {
      if (!std::isfinite(r[c])) throw Error(ErrorCode::ProfileInvalid, std::string(name) + ": non-finite value");
      m(static_cast<Eigen::Index>(i), c) = r[c];
    }
  }
  return m;
}

void read_training_data(const json::Value& labels, const json::Value& tr, Profile& p) {
  for (const auto& l : labels.as_array("training.labels")) p.training_labels.push_back(l.as_string("training.labels"));
  const size_t n = p.training_labels.size();
  if (n == 0 || static_cast<int>(n) != p.training_patches)
    throw Error(ErrorCode::ProfileInvalid, "training.labels: " + std::to_string(n) + " labels for " +
                                               std::to_string(p.training_patches) + " training patches");
  p.training_camera_RGB = read_training_rows(tr.at("camera_RGB"), "training.camera_RGB", n);
  p.training_reference_XYZ = read_training_rows(tr.at("reference_XYZ"), "training.reference_XYZ", n);
  p.has_training_data = true;
}
}  // namespace

std::string profile_to_json(const Profile& p) {
  const ModelInfo& info = model_info(p.model.id);
  json::Value o = json::Value::object();
  o.set("format", "tristim-profile");
  o.set("version", p.version);
  o.set("tristim_version", p.tristim_version.empty() ? std::string(kVersion) : p.tristim_version);
  json::Value model = json::Value::object();
  model.set("id", p.model.id);
  model.set("n_terms", info.n_terms);
  model.set("terms", fields::write(info.term_names));
  model.set("coefficients", fields::write(p.model.coefficients));
  o.set("model", model);
  o.set("objective", objective_id(p.objective));
  json::Value col = json::Value::object();
  col.set("white", fields::write(p.white));
  col.set("illuminant", p.illuminant);
  col.set("observer", p.observer);
  o.set("colorimetry", col);
  json::Value wp = json::Value::object();
  wp.set("enabled", p.white_preserved);
  wp.set("patch", p.white_patch);
  wp.set("RGB", fields::write(p.white_RGB));
  wp.set("XYZ", fields::write(p.white_XYZ));
  o.set("white_preservation", wp);
  json::Value tr = json::Value::object();
  tr.set("patches", p.training_patches);
  tr.set("digest", p.training_digest);
  tr.set("rgb_max", p.rgb_max);
  if (p.has_training_data) {
    tr.set("labels", fields::write(p.training_labels));
    tr.set("camera_RGB", fields::write(Eigen::MatrixXd(p.training_camera_RGB)));
    tr.set("reference_XYZ", fields::write(Eigen::MatrixXd(p.training_reference_XYZ)));
  }
  o.set("training", tr);
  json::Value f = json::Value::object();
  f.set("status", fit_status_name(p.status));
  f.set("message", p.message);
  f.set("condition_number", p.condition_number);
  f.set("iterations", p.iterations);
  f.set("objective_value", p.objective_value);
  o.set("fit", f);
  o.set("metrics", p.metrics.is_object() ? p.metrics : json::Value::object());
  if (p.has_recipe) o.set("recipe", recipe_json(p.recipe));
  if (p.has_linearisation) o.set("linearisation", linearisation_json(p.linearisation));
  return o.dump(2) + "\n";
}

Profile profile_from_json(const std::string& text) {
  const fields::Document d{"tristim-profile", kProfileVersion, "profile", ErrorCode::ProfileInvalid, ErrorCode::ProfileVersion};
  const json::Value o = fields::parse_document(text, d);
  fields::check_document(o, d);
  Profile p;
  p.version = kProfileVersion;
  if (const auto* tv = o.find("tristim_version")) p.tristim_version = tv->as_string("tristim_version");
  const json::Value& model = o.at("model");
  p.model.id = model.at("id").as_string("model.id");
  const ModelInfo* info = nullptr;
  try {
    info = &model_info(p.model.id);
  } catch (const Error&) {
    throw Error(ErrorCode::ProfileInvalid, "unknown model id '" + p.model.id + "' in profile");
  }
  const auto& rows = model.at("coefficients").as_array("model.coefficients");
  if (rows.size() != 3) throw Error(ErrorCode::ProfileInvalid, "model.coefficients must have 3 rows");
  p.model.coefficients.resize(3, info->n_terms);
  for (int c = 0; c < 3; ++c) {
    const auto r = rows[c].as_numbers("model.coefficients row");
    if (static_cast<int>(r.size()) != info->n_terms)
      throw Error(ErrorCode::ProfileInvalid, "model '" + p.model.id + "' needs " + std::to_string(info->n_terms) +
                                                 " coefficients per row, got " + std::to_string(r.size()));
    for (int j = 0; j < info->n_terms; ++j) {
      if (!std::isfinite(r[j])) throw Error(ErrorCode::ProfileInvalid, "non-finite coefficient");
      p.model.coefficients(c, j) = r[j];
    }
  }
  try {
    p.objective = objective_from_id(o.at("objective").as_string("objective"));
  } catch (const Error& e) {
    if (e.code() == ErrorCode::ProfileInvalid) throw;
    throw Error(ErrorCode::ProfileInvalid, e.what());
  }
  const json::Value& col = o.at("colorimetry");
  p.white = read_vec3(col.at("white"), "colorimetry.white");
  if (!(p.white.minCoeff() > 0)) throw Error(ErrorCode::ProfileInvalid, "colorimetry.white must be positive");
  if (const auto* v = col.find("illuminant")) p.illuminant = v->as_string("colorimetry.illuminant");
  if (const auto* v = col.find("observer")) p.observer = v->as_string("colorimetry.observer");
  if (const auto* wp = o.find("white_preservation")) {
    p.white_preserved = wp->at("enabled").as_bool("white_preservation.enabled");
    if (const auto* v = wp->find("patch")) p.white_patch = v->as_string("white_preservation.patch");
    if (const auto* v = wp->find("RGB")) p.white_RGB = read_vec3(*v, "white_preservation.RGB");
    if (const auto* v = wp->find("XYZ")) p.white_XYZ = read_vec3(*v, "white_preservation.XYZ");
  }
  const json::Value& tr = o.at("training");
  p.training_patches = tr.at("patches").as_int("training.patches", 0, limits::kMaxJsonInt);
  p.training_digest = tr.at("digest").as_string("training.digest");
  if (const auto* v = tr.find("rgb_max")) p.rgb_max = v->as_number("training.rgb_max");
  if (!(p.rgb_max > 0)) throw Error(ErrorCode::ProfileInvalid, "training.rgb_max must be positive");
  if (const auto* v = tr.find("labels")) read_training_data(*v, tr, p);
  if (const auto* f = o.find("fit")) {
    if (const auto* v = f->find("status")) p.status = fit_status_from_name(v->as_string("fit.status"));
    if (const auto* v = f->find("message")) p.message = v->as_string("fit.message");
    if (const auto* v = f->find("condition_number"); v && v->is_number()) p.condition_number = v->as_number();
    if (const auto* v = f->find("iterations"); v && v->is_number()) p.iterations = v->as_int("fit.iterations", 0, limits::kMaxJsonInt);
    if (const auto* v = f->find("objective_value"); v && v->is_number()) p.objective_value = v->as_number();
  }
  if (const auto* m = o.find("metrics"); m && m->is_object()) p.metrics = *m;
  else p.metrics = json::Value::object();
  if (const auto* r = o.find("recipe")) {
    p.recipe = recipe_from_json(*r);
    p.has_recipe = true;
  }
  if (const auto* l = o.find("linearisation")) {
    p.linearisation = linearisation_from_json(*l);
    p.has_linearisation = true;
  }
  return p;
}

PatchMatrix profile_input(const Profile& profile, const PatchMatrix& camera_RGB) {
  return profile.has_linearisation ? linearise(profile.linearisation, camera_RGB) : camera_RGB;
}

FitStatus fit_status_from_name(const std::string& s) {
  for (FitStatus st : {FitStatus::Ok, FitStatus::IllConditioned, FitStatus::ExactlyDetermined, FitStatus::IterationLimit})
    if (s == fit_status_name(st)) return st;
  throw Error(ErrorCode::ProfileInvalid, "unknown fit status '" + s + "'");
}

Image3f apply_profile_to_pixels(const Profile& profile, const std::vector<float>& rgb, int width, int height) {
  if (width <= 0 || height <= 0) throw Error(ErrorCode::InvalidArgument, "width and height must be positive");
  const size_t n = 3 * static_cast<size_t>(width) * static_cast<size_t>(height);
  if (rgb.size() != n)
    throw Error(ErrorCode::RowLength, "rgb has " + std::to_string(rgb.size()) + " values, width × height × 3 = " + std::to_string(n));
  return apply_profile(profile, rgb.data(), width, height);
}

PatchMatrix profile_predict(const Profile& profile, const PatchMatrix& camera_RGB) {
  return predict(profile.model, profile_input(profile, camera_RGB));
}

}  // namespace tristim
