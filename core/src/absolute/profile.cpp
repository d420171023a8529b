// Guarnera 2018: the whole chain (eq 4), its fit (sections 3.1-3.2) and the evaluation of
// section 4.1 (rules in tristim/absolute/profile.hpp).
#include "tristim/absolute/profile.hpp"

#include <algorithm>
#include <cmath>

#include "../large_buffer.hpp"
#include "tristim/error.hpp"

namespace tristim {

MethodChoice AbsoluteProfile::linearisation_choice() const {
  MethodChoice c;
  c.method = "Guarnera2018";
  // The table row takes one n and S: the green channel's (the paper's are channel-independent).
  c.parameters["noise_floor"] = normalisation.noise_floor[1];
  c.parameters["saturation"] = normalisation.saturation[1];
  c.parameters["area_R"] = normalisation.areas[0];
  c.parameters["area_G"] = normalisation.areas[1];
  c.parameters["area_B"] = normalisation.areas[2];
  return c;
}

Vec3 AbsoluteProfile::XYZ(const Vec3& L) const { return predict(colour, L); }  // eq (4)

namespace {

Model identity_model(const std::string& transform) {
  const ModelInfo& info = model_info("Guarnera2018-" + transform);
  Model m;
  m.id = info.id;
  m.coefficients = Eigen::MatrixXd::Zero(3, info.n_terms);
  for (int c = 0; c < 3; ++c) m.coefficients(c, c) = 1;  // the first three terms are L(R), L(G), L(B)
  return m;
}

}  // namespace

AbsoluteProfile fit_absolute_Guarnera2018(const std::vector<TrainingStimulus>& stimuli, const Normalisation& n,
                                          const AbsoluteFitOptions& o) {
  if (o.transform != "T1" && o.transform != "To" && o.transform != "T2R")
    throw Error(ErrorCode::UnknownId, "Guarnera 2018 transform '" + o.transform + "' (expected T1, To, T2R)");
  AbsoluteProfile p;
  p.normalisation = n;
  p.luminance = fit_luminance_Guarnera2018(stimuli, n, o.luminance);  // section 3.1
  p.transform = o.transform;
  std::vector<Vec3> L, XYZ;
  for (const auto& s : stimuli) {
    if (s.luminance_set && !o.colour_with_luminance_set) continue;
    if (s.saturated[0] || s.saturated[1] || s.saturated[2]) continue;
    L.push_back(stimulus_luminance(s, n, p.luminance));
    XYZ.push_back(s.XYZ);
  }
  p.colour_stimuli = static_cast<int>(L.size());
  if (L.empty()) {
    p.colour = identity_model(o.transform);
    p.colour_message = "no chromatic stimuli: M is the identity (eq 9, exact for equal-tristimulus light only)";
    return p;
  }
  PatchMatrix Lm(L.size(), 3), Xm(L.size(), 3);
  for (size_t i = 0; i < L.size(); ++i) {
    Lm.row(i) = L[i].transpose();
    Xm.row(i) = XYZ[i].transpose();
  }
  FitOptions fo;
  fo.objective = Objective::PatternSearch;  // eqs (11)-(12), Algorithm 2
  fo.psm = o.psm;
  const FitResult r = fit_Guarnera2018(Lm, Xm, o.transform, fo);
  p.colour = r.model;
  p.colour_status = r.status;
  p.colour_message = r.message;
  p.colour_objective = r.objective_value;
  return p;
}

void check_profile_frame(const AbsoluteProfile& profile, const RawImage& frame, const std::string& what) {
  if (!profile.make.empty() || !profile.model.empty())
    if (frame.meta.make != profile.make || frame.meta.model != profile.model)
      throw Error(ErrorCode::FrameMismatch, what + " comes from " + frame.meta.make + " " + frame.meta.model +
                                                " but the profile was made for " + profile.make + " " + profile.model);
  if (profile.width > 0 && (frame.width != profile.width || frame.height != profile.height))
    throw Error(ErrorCode::FrameMismatch, what + " is " + std::to_string(frame.width) + "x" +
                                              std::to_string(frame.height) + " but the profile's fall-off was fitted on " +
                                              std::to_string(profile.width) + "x" + std::to_string(profile.height));
}

void luminance_to_XYZ(const AbsoluteProfile& profile, const std::vector<float>& L, std::vector<float>& XYZ) {
  detail::assign_large(XYZ, L.size(), 0.0f);
  apply_to_image(profile.colour, L.data(), L.size() / 3, XYZ.data());  // eq (4)
}

AbsoluteImage apply_absolute(const AbsoluteProfile& profile, const std::vector<const RawImage*>& frames,
                             const std::vector<ExposureSettings>& given) {
  if (frames.empty()) throw Error(ErrorCode::InvalidArgument, "no frames to apply the profile to");
  if (!given.empty() && given.size() != frames.size())
    throw Error(ErrorCode::InvalidArgument, "give one exposure per frame, or none (read from the metadata)");
  std::vector<ExposureSettings> exposures;
  for (size_t i = 0; i < frames.size(); ++i) {
    const std::string what = "frame " + std::to_string(i + 1);
    check_profile_frame(profile, *frames[i], what);
    exposures.push_back(given.empty() ? exposure_from_metadata(frames[i]->meta, what) : given[i]);
  }
  AbsoluteImage out;
  if (profile.fusion == FusionMode::Recursive) {
    out.luminance = select_exposures_Guarnera2018(frames, exposures, profile.normalisation, profile.luminance);
  } else {
    ExposureFusion fusion(profile.normalisation, profile.luminance, frames[0]->width, frames[0]->height);
    for (size_t i = 0; i < frames.size(); ++i) fusion.add(*frames[i], exposures[i]);
    out.luminance = fusion.finish();
  }
  luminance_to_XYZ(profile, out.luminance.L, out.XYZ);
  return out;
}

Vec3 white_Guarnera2018(const Vec3& w, double max_luminance) {
  if (!(w[1] > 0)) throw Error(ErrorCode::InvalidArgument, "the white patch needs Y > 0");
  return Vec3(w[0] * max_luminance / w[1], max_luminance, w[2] * max_luminance / w[1]);  // eq (16)
}

Vec3 white_equal_energy(double max_luminance) { return Vec3::Constant(max_luminance); }

AbsoluteMetrics evaluate_absolute(const PatchMatrix& est, const PatchMatrix& ref, const Vec3& white) {
  AbsoluteMetrics m;
  m.white = white;
  m.metrics = evaluate(est, ref, white);
  double sum = 0;
  int count = 0;
  for (Eigen::Index i = 0; i < ref.rows(); ++i)
    if (ref(i, 1) > 0) {
      sum += std::fabs(est(i, 1) - ref(i, 1)) / ref(i, 1);
      ++count;
    }
  m.relative_Y_error = count ? sum / count : 0;
  for (int c = 0; c < 3; ++c) {
    std::vector<double> e;
    for (Eigen::Index i = 0; i < ref.rows(); ++i) e.push_back(std::fabs(est(i, c) - ref(i, c)));
    m.median_absolute_error[c] = summarize(e).median;
  }
  return m;
}

}  // namespace tristim
