// Declarations: share links and project files (tristim/share/link.hpp). The page's Share button
// (shareSample -> the payload text, shareLink -> the link; shareTraining for a recipe with several
// chart images, on the union of their training sets (fitTraining's); shareAbsolute for an absolute recipe of
// per-patch rows), opening a link (reproduceLink ->
// Reproduction; with the source image at hand reproduceLinkImage samples it again), project files
// (projectFile -> Uint8Array, openProject), the SHA-256 of bytes, and version 2's preset deflate
// dictionary (shareLinkDictionary: for tools and tests that read a link's content themselves).
#include "tristim/share/link.hpp"
#include "tristim/share/sha256.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::value_object;
using wasm::def;

namespace {
/// shareTraining(recipe, training, sources): the payload of characterise(recipe, training) — for a
/// fit on several chart images, `training` is trainingUnion's (as the fit handler's fitTraining).
std::string share_training_payload(const Recipe& recipe, const TrainingSet& training, const std::vector<ShareSource>& sources) {
  return encode_share_payload(share_payload(characterise(recipe, training), training, sources));
}
}  // namespace

EMSCRIPTEN_BINDINGS(tristim_share) {
  { using S = ShareSource; value_object<S>("ShareSource") FIELD(name) FIELD(sha256); }
  { using S = ShareResults; value_object<S>("ShareResults") FIELD(text) FIELD(digest); }
  { using S = ShareDifference; value_object<S>("ShareDifference") FIELD(name) FIELD(expected) FIELD(actual); }
  { using S = Reproduction; value_object<S>("Reproduction") FIELD(verdict) FIELD(kind) FIELD(expected_version)
      FIELD(actual_version) FIELD(expected) FIELD(actual) FIELD(differences) FIELD(profile) FIELD(payload) FIELD(resampled); }
  { using S = ProjectImage; value_object<S>("ProjectImage") FIELD(name) FIELD(bytes); }
  { using S = ProjectContents; value_object<S>("ProjectContents") FIELD(payload) FIELD(images) FIELD(session); }

  def<&share_sample_payload>("shareSample");
  def<&share_training_payload>("shareTraining");
  def<&share_absolute_payload>("shareAbsolute");
  def<&share_link>("shareLink");
  def<&share_link_limit>("shareLinkLimit");
  def<&share_link_dictionary>("shareLinkDictionary");
  def<&reproduce_link>("reproduceLink");
  def<&reproduce_link_image>("reproduceLinkImage");
  def<&project_file>("projectFile");
  def<&open_project>("openProject");
  def<static_cast<std::string (*)(const std::vector<std::uint8_t>&)>(&sha256_hex)>("sha256");
}
