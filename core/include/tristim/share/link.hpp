// Reproducible profile links (docs/link-format.md): everything needed to recompute a profile —
// the recipe, the per-patch camera RGB, the reference (a built-in chart by id, or inline XYZ), the
// tristim version, the SHA-256 of each source image and the expected results — as a compact text
// that fits in a URL fragment:
//
//   payload = "2." base64url(data) "." base64url(SHA-256(data)[0..11]), data = deflate-raw(content,
//             preset dictionary)
//   content = JSON (the recipe as an RFC 7386 merge patch against a pinned default recipe, the
//             patches' ids only when they differ from the chart's, the source names, the expected
//             results' text with its numbers cut out) NUL binary (each source's SHA-256, the
//             results' numbers as exact decimals, the camera RGB [and inline XYZ] as IEEE-754
//             doubles, byte-shuffled so that their exponent bytes compress)
//   link    = <page address> "#tristim=" payload
//
// Version 1 links ("1.": the whole JSON document, digest and hex SHA-256 included, doubles as
// they are, the check over the content) are still read. The trailing check catches a changed or
// truncated payload before anything is read from it; deflate-raw is RFC 1951 (zlib's raw mode natively and in wasm; the page
// uses the module, never CompressionStream, so both sides run the same code). Reading never
// inflates more than kMaxLinkInflatedBytes (a decompression bomb is refused while it inflates).
// The check and the digest identify data, they do not authenticate it: anyone can make a link.
//
// Opening a link (reproduce) recomputes the profile from the data in it and compares the
// expected results — coefficients to 10 significant digits, metrics to 6 — with the new ones:
// equal digests → "reproduced", else "differs" with both results line by line.
//
// A project file (.tristim) holds the same payload with the source images themselves
// (project_to_bytes / project_from_bytes, below).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "tristim/absolute/characterise.hpp"
#include "tristim/absolute/recipe.hpp"
#include "tristim/capture/raw.hpp"
#include "tristim/chart/layout.hpp"
#include "tristim/io/json.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/profile/recipe.hpp"

namespace tristim {

/// The link format written ("2."); version 1 links are read too.
constexpr int kLinkVersion = 2;
/// The version of the payload's JSON document (share_payload_json: project files, reproduce's
/// report): unchanged by the link's version 2, which encodes the same document more compactly.
constexpr int kPayloadVersion = 1;
/// Project files' format version ("TRISTIM-PROJECT 1").
constexpr int kProjectVersion = 1;
/// Refused beyond this many characters of link or payload text (LimitExceeded).
constexpr std::size_t kMaxLinkChars = 1u << 20;
/// Inflation stops with LimitExceeded when the payload JSON would exceed this (a bomb).
constexpr std::size_t kMaxLinkInflatedBytes = 1u << 20;
/// Links longer than this are not offered: the page offers a project file instead (some mail
/// and chat programs cut longer URLs; browsers accept far more).
constexpr std::size_t kLinkLengthLimit = 16000;
inline std::size_t share_link_limit() { return kLinkLengthLimit; }

/// A source image the profile was sampled from (not in the link: its identity only).
struct ShareSource {
  std::string name;    ///< file name as the user gave it
  std::string sha256;  ///< 64 lower-case hex digits
};

/// The expected results of a profile as text lines "name value …" (docs/link-format.md).
struct ShareResults {
  std::string text;    ///< one line per result, "\n"-terminated
  std::string digest;  ///< "sha256:" + SHA-256(text), hex
};

struct SharePayload {
  int version = kPayloadVersion;  ///< the JSON document's version
  std::string tristim_version;
  std::string kind = "relative";          ///< "relative" (Recipe) | "absolute" (AbsoluteRecipe)
  Recipe recipe;                          ///< kind "relative"
  AbsoluteRecipe absolute;                ///< kind "absolute": its stimuli rows carry the data
  std::vector<std::string> labels;        ///< relative: training patches as the user's data spell them
  PatchMatrix camera_RGB;                 ///< relative: N × 3, as sampled (before linearisation)
  PatchMatrix reference_XYZ;              ///< relative, reference "file" only: N × 3 (else 0 × 3)
  std::vector<ShareSource> sources;
  ShareResults expected;
};

/// Results of a relative profile: model, objective, status, the coefficients (and a fitted
/// linearisation stage's parameters) to 10 significant digits, the training and leave-one-out
/// CIEDE2000 summaries and mean ΔE*ab, ΔE94 to 6 significant digits.
ShareResults share_results(const Profile& profile);
/// Results of an absolute profile: transform, the colour matrix and the eq (8) curves to 10
/// significant digits, the training figures' ΔE94, ΔE00 and relative Y error to 6.
ShareResults share_results(const AbsoluteProfile& profile);

/// The payload of a relative characterisation and the training set it was fitted on.
SharePayload share_payload(const Characterisation& characterisation, const TrainingSet& training,
                           const std::vector<ShareSource>& sources = {});
/// The payload of an absolute characterisation. Error(InvalidArgument) when its recipe names
/// frames (bracket, lens cap, flat, region rows): those are not in a link (use a project file).
SharePayload share_payload(const AbsoluteCharacterisation& characterisation);

/// The payload as one JSON document (the recipe whole, patch values inline): what a project file
/// holds and what reproduce_share reports; a link carries it in the compact form above.
json::Value share_payload_json(const SharePayload& payload);
/// Strict reader (ParseError naming the field; ProfileVersion for another version; the recipe
/// readers' codes for the recipe).
SharePayload share_payload_from_json(const json::Value& value);

/// "2.<data>.<check>" (see the header comment).
std::string encode_share_payload(const SharePayload& payload);
/// The version 1 text of a payload ("1.<data>.<check>"), as tristim wrote links before version 2:
/// for tests and for a reader that only knows version 1.
std::string encode_share_payload_v1(const SharePayload& payload);
/// Reads a link (its "#tristim=" fragment), or a bare payload, of version 1 or 2. Errors:
/// LimitExceeded (text longer than kMaxLinkChars, or inflating beyond kMaxLinkInflatedBytes),
/// ProfileVersion (a payload of another format version), ParseError (not a payload, bad base64url, a truncated or
/// corrupt deflate stream, a check that does not match, malformed JSON or fields).
SharePayload decode_share_payload(std::string_view text);
/// base + "#tristim=" + payload (base's own fragment, if any, replaced).
std::string share_link(const std::string& base, const std::string& payload);

/// Whether a relative payload carries its reference XYZ inline: a user's reference ("file"), or a
/// recipe with several chart images (issue 48: the union of several references' patches).
bool share_inline_reference(const Recipe& recipe);

/// The training set a relative payload carries (reference XYZ from the built-in chart by id, or
/// inline). Error(PatchMismatch) when a patch is not in the recipe's chart.
TrainingSet share_training(const SharePayload& payload);

/// Fits `recipe` on a chart sample paired with `reference` (training_set) and returns the encoded
/// payload: the page's Share button.
std::string share_sample_payload(const Recipe& recipe, const ChartSample& sample, const ReferenceChart& reference,
                                 const std::vector<ShareSource>& sources);

/// Fits an absolute recipe whose stimuli are per-patch rows (no frames) and returns the encoded
/// payload (share_payload's errors for a recipe that names frames).
std::string share_absolute_payload(const AbsoluteRecipe& recipe);

/// The training set of `recipe` sampled from a chart image as `tristim fit --recipe --raw` samples
/// it: the recipe's layout, corners and area, its light trap measured again; a stored (TIFF/PNG/
/// JPEG) image sets capture.saturation when the recipe has none. `reference`: null for the recipe's
/// built-in chart. Error(InvalidArgument) when the recipe has no corners.
TrainingSet sample_training(Recipe& recipe, const RawImage& image, const ReferenceChart* reference = nullptr);

struct ShareDifference {
  std::string name, expected, actual;  ///< a results line's name and both values ("" absent)
};

struct Reproduction {
  std::string verdict;               ///< "reproduced" | "differs"
  std::string kind;
  std::string expected_version, actual_version;  ///< tristim versions: the link's, this one
  ShareResults expected, actual;
  std::vector<ShareDifference> differences;
  std::string profile;               ///< the recomputed profile JSON
  std::string payload;               ///< the payload read, as JSON text (share_payload_json)
  bool resampled = false;            ///< the patches were sampled again from the source image
};

/// Recomputes the profile from the payload and compares its results with the expected ones.
Reproduction reproduce_share(const SharePayload& payload);
/// Whether a payload's patches can be sampled again from its source image alone: a relative
/// recipe with chart corners and no dark frames or flat field (those frames are not in a link).
bool can_resample(const SharePayload& payload);
/// reproduce_share(decode_share_payload(text)).
Reproduction reproduce_link(const std::string& text);
/// reproduce_share with the source image at hand: its SHA-256 must be one of the payload's sources
/// (Error(PatchMismatch) otherwise); it is decoded and sampled again (sample_training), so the
/// sampling is reproduced too. InvalidArgument unless can_resample(payload).
Reproduction reproduce_share_image(const SharePayload& payload, const std::vector<std::uint8_t>& image_bytes);
Reproduction reproduce_link_image(const std::string& text, const std::vector<std::uint8_t>& image_bytes);
json::Value reproduction_json(const Reproduction& reproduction);

// ---- base64url and deflate-raw (RFC 4648 section 5, RFC 1951) ----------------------------------

std::string base64url_encode(std::string_view bytes);
/// Error(ParseError) naming the offset of a character outside the alphabet (padding '=' accepted
/// at the end only), an impossible length, or a last character with unused bits set (only the
/// canonical encoding is read, so no character can change without the bytes changing).
std::string base64url_decode(std::string_view text, const std::string& what);
/// Raw deflate at level 9; `dictionary`: a preset dictionary (zlib's deflateSetDictionary), which
/// the reader must pass to inflate_raw too; `block_end` > 0: a deflate block ends after that many
/// bytes (zlib's Z_BLOCK), so that what follows (e.g. incompressible bytes) gets a block of its own.
std::string deflate_raw(std::string_view bytes, std::string_view dictionary = {}, std::size_t block_end = 0);
/// Error(LimitExceeded) as soon as the output would exceed `max_bytes`; Error(ParseError) for a
/// corrupt or truncated stream, or bytes after its end.
std::string inflate_raw(std::string_view bytes, std::size_t max_bytes, const std::string& what,
                        std::string_view dictionary = {});
/// The preset dictionary of version 2 links (docs/link-format.md gives it verbatim).
const std::string& share_link_dictionary();

// ---- project files (.tristim) --------------------------------------------------------------------
//
//   "TRISTIM-PROJECT 1\n" <decimal byte length of the header>\n <header JSON> <image bytes…>
//   header: {"format": "tristim-project", "version": 1, "payload": <share payload JSON>,
//            "images": [{"name", "sha256", "offset", "size"}], "session": {…}}
// offsets count from the first byte after the header; every image's SHA-256 is checked on reading.

struct ProjectImage {
  std::string name;
  std::vector<std::uint8_t> bytes;
};

struct Project {
  SharePayload payload;
  std::vector<ProjectImage> images;  ///< optional: the source images themselves
  json::Value session = json::Value::object();  ///< the page's own state (opaque here)
};

constexpr std::size_t kMaxProjectBytes = 1024u << 20;  ///< 1 GiB

std::string project_to_bytes(const Project& project);
/// Errors: ParseError (not a project file, a malformed header, an image outside the file or whose
/// SHA-256 differs), ProfileVersion, LimitExceeded (beyond kMaxProjectBytes), the payload's codes.
Project project_from_bytes(std::string_view bytes);
/// Whether `bytes` start like a project file.
bool is_project_file(std::string_view bytes);
/// The page's export: a project of an encoded payload (encode_share_payload), the session's
/// images and the page's own state as JSON text (kept as it is).
std::vector<std::uint8_t> project_file(const std::string& payload, const std::vector<ProjectImage>& images,
                                       const std::string& session_json);

/// A project file opened (the page's import): its payload encoded as a link's, its images, its
/// session as JSON text.
struct ProjectContents {
  std::string payload;
  std::vector<ProjectImage> images;
  std::string session;
};
ProjectContents open_project(const std::vector<std::uint8_t>& bytes);

/// A project recomputed: from its source image when it holds one the payload names and
/// can_resample (reproduce_share_image: the sampling too), else from its patch data.
Reproduction reproduce_project(const Project& project);

}  // namespace tristim
