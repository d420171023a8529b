// Profile JSON: write, read back exactly, digest the training data.
#include "tristim/profile/profile.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>

#include "tristim/error.hpp"
#include "tristim/profile/characterise.hpp"  // ChartFigures (the "charts" tristim fit writes)
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
const fields::Document kProfileDocument{"tristim-profile", kProfileVersion, "profile", ErrorCode::ProfileInvalid,
                                        ErrorCode::ProfileVersion};
}  // namespace

json::Value profile_json(const Profile& profile) { return fields::write_document(profile, kProfileDocument); }

std::string profile_to_json(const Profile& profile) { return profile_json(profile).dump(2) + "\n"; }

Profile profile_from_document(const json::Value& document) {
  Profile p;
  fields::check_document(document, kProfileDocument);
  // What `tristim fit` writes beside the profile's members (its bootstrap intervals, the figures
  // per chart, a corrected 3x3's mu) is known and not kept; the figures per chart are checked by
  // their field list (ChartFigures, profile/characterise.hpp: an unknown member refused).
  const fields::Context context{ErrorCode::ProfileInvalid, ""};
  fields::read_members(document, p, context, "", {"format", "version", "bootstrap", "charts", "corrected_3x3"});
  if (const json::Value* charts = document.find("charts")) {
    std::vector<ChartFigures> figures;
    fields::read(*charts, figures, context, "charts");
  }
  p.version = kProfileVersion;
  const auto n = static_cast<Eigen::Index>(p.training_labels.size());
  if (p.training_camera_RGB.rows() != n || p.training_reference_XYZ.rows() != n)
    throw Error(ErrorCode::ProfileInvalid, "training.camera_RGB and training.reference_XYZ: " + std::to_string(n) +
                                               " rows each, one per training.labels entry");
  return p;
}

Profile profile_from_json(const std::string& text) { return profile_from_document(fields::parse_document(text, kProfileDocument)); }

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

// The profile's field list: its members in the order of the format (profile.hpp's header comment),
// in sections. Members the model implies (n_terms, terms) are written for readers and not read.
namespace tristim::fields {
namespace {
using P = Profile;

/// `f`, kept at its C++ default when the profile leaves it out.
Field<P> optional(Field<P> f) {
  f.required = false;
  return f;
}
/// A number member written as a number (null when not finite) and read back when it is one (a
/// null keeps the default).
template <double P::*M>
Field<P> figure(const char* name) {
  return {name, [](const P& p) { return json::Value(p.*M); },
          [](const json::Value& v, P& p, const Context& c, const std::string& path) {
            if (!v.is_null()) Codec<double>::read(v, p.*M, c, path);
          },
          nullptr, false};
}
void read_nothing(const json::Value&, P&, const Context&, const std::string&) {}

const FieldList<P>& model_fields() {
  static const FieldList<P> f = {
      {"id", [](const P& p) { return json::Value(p.model.id); },
       [](const json::Value& v, P& p, const Context& c, const std::string& path) {
         Codec<std::string>::read(v, p.model.id, c, path);
         try {
           model_info(p.model.id);
         } catch (const Error&) {
           c.refuse("unknown model id '" + p.model.id + "' in profile");
         }
       }},
      {"n_terms", [](const P& p) { return json::Value(model_info(p.model.id).n_terms); }, read_nothing},
      {"terms", [](const P& p) { return write(model_info(p.model.id).term_names); }, read_nothing},
      {"coefficients", [](const P& p) { return write(p.model.coefficients); },
       [](const json::Value& v, P& p, const Context& c, const std::string& path) {
         read(v, p.model.coefficients, c, path);
         check_coefficient_shape(p.model, model_info(p.model.id));
       }},
  };
  return f;
}
const FieldList<P>& colorimetry_fields() {
  static const FieldList<P> f = {
      {"white", [](const P& p) { return write(p.white); },
       [](const json::Value& v, P& p, const Context& c, const std::string& path) {
         read(v, p.white, c, path);
         if (!(p.white.minCoeff() > 0)) c.refuse("'" + path + "' must be positive");
       }},
      member<&P::illuminant>("illuminant", false),
      member<&P::observer>("observer", false),
  };
  return f;
}
const FieldList<P>& white_preservation_fields() {
  static const FieldList<P> f = {member<&P::white_preserved>("enabled"), member<&P::white_patch>("patch", false),
                                 member<&P::white_RGB>("RGB", false), member<&P::white_XYZ>("XYZ", false)};
  return f;
}
/// training.camera_RGB / reference_XYZ: rows of 3 numbers (their count is checked against the
/// labels once all are read).
template <PatchMatrix P::*M>
Field<P> training_rows(const char* name) {
  return {name, [](const P& p) { return write(Eigen::MatrixXd(p.*M)); },
          [](const json::Value& v, P& p, const Context& c, const std::string& path) {
            Eigen::MatrixXd m;
            read(v, m, c, path);
            if (m.rows() > 0 && m.cols() != 3) c.refuse("'" + path + "' must have rows of 3 values");
            p.*M = m.rows() > 0 ? PatchMatrix(m) : PatchMatrix(0, 3);
          },
          [](const P& p) { return p.has_training_data; }, false};
}
const FieldList<P>& training_fields() {
  static const FieldList<P> f = {
      {"patches", [](const P& p) { return json::Value(p.training_patches); },
       [](const json::Value& v, P& p, const Context& c, const std::string& path) {
         read(v, p.training_patches, c, path);
         if (p.training_patches < 0) c.refuse("'" + path + "' must not be negative");
       }},
      member<&P::training_digest>("digest"),
      {"rgb_max", [](const P& p) { return json::Value(p.rgb_max); },
       [](const json::Value& v, P& p, const Context& c, const std::string& path) {
         read(v, p.rgb_max, c, path);
         if (!(p.rgb_max > 0)) c.refuse("'" + path + "' must be positive");
       },
       nullptr, false},
      {"labels", [](const P& p) { return write(p.training_labels); },
       [](const json::Value& v, P& p, const Context& c, const std::string& path) {
         read(v, p.training_labels, c, path);
         const size_t n = p.training_labels.size();
         if (n == 0 || static_cast<int>(n) != p.training_patches)
           c.refuse("'" + path + "': " + std::to_string(n) + " labels for " + std::to_string(p.training_patches) +
                    " training patches");
         p.has_training_data = true;
       },
       [](const P& p) { return p.has_training_data; }, false},
      training_rows<&P::training_camera_RGB>("camera_RGB"),
      training_rows<&P::training_reference_XYZ>("reference_XYZ"),
  };
  return f;
}
const FieldList<P>& fit_fields() {
  static const FieldList<P> f = {
      {"status", [](const P& p) { return json::Value(fit_status_name(p.status)); },
       [](const json::Value& v, P& p, const Context& c, const std::string& path) {
         std::string name;
         read(v, name, c, path);
         p.status = fit_status_from_name(name);
       },
       nullptr, false},
      member<&P::message>("message", false),
      figure<&P::condition_number>("condition_number"),
      {"iterations", [](const P& p) { return json::Value(p.iterations); },
       [](const json::Value& v, P& p, const Context& c, const std::string& path) {
         if (v.is_null()) return;
         read(v, p.iterations, c, path);
         if (p.iterations < 0) c.refuse("'" + path + "' must not be negative");
       },
       nullptr, false},
      figure<&P::objective_value>("objective_value"),
  };
  return f;
}
}  // namespace

TRISTIM_FIELDS_DEFINE(
    Profile,
    {"tristim_version", [](const P& p) { return json::Value(p.tristim_version.empty() ? std::string(kVersion) : p.tristim_version); },
     [](const json::Value& v, P& p, const Context& c, const std::string& path) { read(v, p.tristim_version, c, path); },
     nullptr, false},
    section<P, &model_fields>("model"),
    {"objective", [](const P& p) { return json::Value(objective_id(p.objective)); },
     [](const json::Value& v, P& p, const Context& c, const std::string& path) {
       std::string id;
       read(v, id, c, path);
       try {
         p.objective = objective_from_id(id);
       } catch (const Error& e) {
         c.refuse(e.what());
       }
     }},
    section<P, &colorimetry_fields>("colorimetry"),
    optional(section<P, &white_preservation_fields>("white_preservation")),
    section<P, &training_fields>("training"),
    optional(section<P, &fit_fields>("fit")),
    {"metrics", [](const P& p) { return p.metrics.is_object() ? p.metrics : json::Value::object(); },
     [](const json::Value& v, P& p, const Context&, const std::string&) { p.metrics = v.is_object() ? v : json::Value::object(); },
     nullptr, false},
    {"recipe", [](const P& p) { return recipe_json(p.recipe); },
     [](const json::Value& v, P& p, const Context&, const std::string&) {
       p.recipe = recipe_from_json(v);
       p.has_recipe = true;
     },
     [](const P& p) { return p.has_recipe; }, false},
    {"linearisation", [](const P& p) { return linearisation_json(p.linearisation); },
     [](const json::Value& v, P& p, const Context&, const std::string&) {
       p.linearisation = linearisation_from_json(v);
       p.has_linearisation = true;
     },
     [](const P& p) { return p.has_linearisation; }, false});

}  // namespace tristim::fields
