// Share links and project files (share/link.hpp): SHA-256 against FIPS 180-2's examples, base64url
// and deflate-raw round trips, a planted fit that reproduces from its link, and every planted
// damage (a changed byte, a cut, a bomb, a future version) refused with its code. Links are
// written in format version 2; a version 1 link (a fixture made before version 2) is still read.
#include <Eigen/LU>
#include <random>

#include "shell.hpp"
#include "test_support.hpp"
#include "tristim/absolute/example.hpp"
#include "tristim/profile/characterise.hpp"
#include "tristim/share/link.hpp"
#include "tristim/share/sha256.hpp"

using namespace tristim;
using tristim::test::require_code;

namespace {

/// A cc24 recipe and camera RGB planted from a known 3×3 (XYZ = M·RGB): the fit must recover M.
struct Planted {
  Recipe recipe;
  TrainingSet training;
  Eigen::Matrix3d M;
};

Planted planted(const std::string& model = "matrix-3x3", const std::string& objective = "ls") {
  Planted p;
  p.recipe.reference.chart = "cc24";
  p.recipe.sampling.layout.chart = "cc24";
  p.recipe.characterisation.model = model;
  p.recipe.characterisation.objective = MethodChoice{objective, {}, {}};
  p.recipe = complete_recipe(p.recipe);
  const ReferenceChart ref = recipe_reference(p.recipe);
  p.M << 0.61, 0.25, 0.09, 0.30, 0.62, 0.08, 0.02, 0.11, 0.83;
  PatchMatrix XYZ(ref.XYZ.size(), 3), RGB(ref.XYZ.size(), 3);
  for (size_t i = 0; i < ref.XYZ.size(); ++i) {
    XYZ.row(i) = ref.XYZ[i].transpose();
    RGB.row(i) = (p.M.inverse() * ref.XYZ[i]).transpose() * 40.0;  // DN-like scale
  }
  p.training = training_set(p.recipe, ref.labels, RGB, XYZ);
  return p;
}

std::string payload_of(const Planted& p) {
  const Characterisation c = characterise(p.recipe, p.training);
  return encode_share_payload(share_payload(c, p.training, {{"chart.dng", sha256_hex("raw bytes")}}));
}

}  // namespace

TEST_CASE("SHA-256 gives FIPS 180-2's example digests", "[share]") {
  CHECK(sha256_hex("abc") == "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  CHECK(sha256_hex("") == "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  CHECK(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq") ==
        "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  Sha256 h;  // one million 'a', fed unevenly: the incremental path
  const std::string chunk(997, 'a');
  std::size_t left = 1000000;
  while (left > 0) {
    const std::size_t n = std::min(left, chunk.size());
    h.update(chunk.data(), n);
    left -= n;
  }
  std::string hex;
  for (auto b : h.digest()) {
    char buf[3];
    std::snprintf(buf, sizeof buf, "%02x", b);
    hex += buf;
  }
  CHECK(hex == "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST_CASE("base64url and deflate-raw round-trip every length", "[share]") {
  std::mt19937 rng(7);
  for (std::size_t n = 0; n < 300; n += 7) {
    std::string bytes(n, '\0');
    for (auto& b : bytes) b = static_cast<char>(rng() & 0xff);
    const std::string b64 = base64url_encode(bytes);
    CHECK(b64.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_") == std::string::npos);
    CHECK(base64url_decode(b64, "t") == bytes);
    CHECK(inflate_raw(deflate_raw(bytes), n, "t") == bytes);
  }
  CHECK(base64url_encode("abc") == "YWJj");  // RFC 4648 section 10: BASE64("foob") = "Zm9vYg=="
  CHECK(base64url_encode("foob") == "Zm9vYg");
  CHECK(base64url_decode("Zm9vYg==", "t") == "foob");
  require_code([] { base64url_decode("Zm9v+g", "t"); }, ErrorCode::ParseError);
  require_code([] { base64url_decode("Zm9vY", "t"); }, ErrorCode::ParseError);
  require_code([] { base64url_decode("Zm9vYh", "t"); }, ErrorCode::ParseError);  // "Zm9vYg" with a spare bit set
  const std::string big(100000, ' ');
  require_code([&] { inflate_raw(deflate_raw(big), 65536, "t"); }, ErrorCode::LimitExceeded);
  const std::string d = deflate_raw("hello hello hello");
  require_code([&] { inflate_raw(d.substr(0, d.size() - 2), 1000, "t"); }, ErrorCode::ParseError);
  require_code([&] { inflate_raw(d + "x", 1000, "t"); }, ErrorCode::ParseError);
}

TEST_CASE("a planted fit reproduces from its link and recovers the planted matrix", "[share]") {
  const Planted p = planted();
  const std::string payload = payload_of(p);
  const std::string link = share_link("http://127.0.0.1:8080/index.html#old", payload);
  CHECK(link == "http://127.0.0.1:8080/index.html#tristim=" + payload);
  for (const std::string& text : {payload, link, "  " + link + "\n", "http://x/#a=1&tristim=" + payload + "&b=2"}) {
    const SharePayload back = decode_share_payload(text);
    CHECK(back.kind == "relative");
    CHECK(back.labels == p.training.labels);
    CHECK(back.camera_RGB == p.training.camera_RGB);  // bit for bit
    CHECK(back.reference_XYZ.rows() == 0);            // built-in chart: by id
    REQUIRE(back.sources.size() == 1);
    CHECK(back.sources[0].sha256 == sha256_hex("raw bytes"));
    const Reproduction r = reproduce_share(back);
    CHECK(r.verdict == "reproduced");
    CHECK(r.differences.empty());
    CHECK(r.actual.digest == back.expected.digest);
  }
  // The coefficients line holds the planted M (to the 10 digits the results keep).
  const SharePayload back = decode_share_payload(payload);
  const auto at = back.expected.text.find("coefficients ");
  REQUIRE(at != std::string::npos);
  std::istringstream in(back.expected.text.substr(at + 13));
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      double v = 0;
      in >> v;
      CHECK(v == Approx(p.M(r, c) / 40).margin(1e-9));  // RGB was planted × 40
    }
  CHECK(payload.size() < 1100);  // version 2: 24 patches, a 3×3 (version 1: ~1,700)
}

TEST_CASE("a version 1 link is still read and reproduces, and version 2 carries the same payload, shorter", "[share]") {
  // A link made before version 2 (tests/fuzz/corpus/share_payload/passport-link.txt: "L" + link).
  std::string v1 = tristim::test::read_test_file("tests/fuzz/corpus/share_payload/passport-link.txt").substr(1);
  REQUIRE(v1.find("#tristim=1.") != std::string::npos);
  const SharePayload old = decode_share_payload(v1);
  CHECK(reproduce_share(old).verdict == "reproduced");
  const std::string v2 = encode_share_payload(old);
  REQUIRE(v2.rfind("2.", 0) == 0);
  CHECK(v2.size() + 400 < v1.size());
  const SharePayload back = decode_share_payload(v2);
  CHECK(share_payload_json(back).dump() == share_payload_json(old).dump());  // the same document, bit for bit
  CHECK(encode_share_payload_v1(back) == v1.substr(v1.find('=') + 1));       // and written as version 1, the same link
}

TEST_CASE("version 2 links: patch ids only when not in the chart order, the results text exactly, numbers or not", "[share]") {
  const Planted p = planted();
  const Characterisation c = characterise(p.recipe, p.training);
  SharePayload s = share_payload(c, p.training);
  auto content_of = [](const std::string& payload) {
    const std::size_t a = payload.find('.'), b = payload.rfind('.');
    return inflate_raw(base64url_decode(payload.substr(a + 1, b - a - 1), "t"), 1u << 20, "t", share_link_dictionary());
  };
  CHECK(content_of(encode_share_payload(s)).find("\"ids\"") == std::string::npos);
  // Another order (or a subset) travels with its ids.
  std::swap(s.labels[0], s.labels[1]);
  const std::string swapped = encode_share_payload(s);
  CHECK(content_of(swapped).find("\"ids\":[\"" + s.labels[0] + "\",\"" + s.labels[1] + "\"") != std::string::npos);
  CHECK(decode_share_payload(swapped).labels == s.labels);
  // Numbers as %g prints them come back as they were; tokens that only look like numbers too.
  s.expected.text = "model matrix-3x3\ncoefficients 0 -0 100 0.5 -0.0001234567891 1.5e-05 -9.999999999e+100 1e-300 12345678901234567\n"
                    "odd 007 1.50 .5 5. 1e5 1e+5 -e+05 nan inf null 2.2x x2.2 0.000 \n\n  trailing 3";
  const SharePayload back = decode_share_payload(encode_share_payload(s));
  CHECK(back.expected.text == s.expected.text);
  CHECK(back.expected.digest == "sha256:" + sha256_hex(s.expected.text));
}

TEST_CASE("a link whose data give other numbers differs, with both results", "[share]") {
  const Planted p = planted();
  const Characterisation c = characterise(p.recipe, p.training);
  SharePayload s = share_payload(c, p.training);
  s.camera_RGB(3, 1) *= 1.01;  // as another sampling would
  const Reproduction r = reproduce_share(decode_share_payload(encode_share_payload(s)));
  CHECK(r.verdict == "differs");
  REQUIRE(!r.differences.empty());
  CHECK(r.differences[0].name == "coefficients");
  CHECK(r.differences[0].expected != r.differences[0].actual);
  const json::Value j = reproduction_json(r);
  CHECK(j.at("verdict").as_string() == "differs");
  CHECK(j.at("expected").at("digest").as_string() != j.at("actual").at("digest").as_string());
}

TEST_CASE("an inline reference travels in the link", "[share]") {
  Planted p = planted("Finlayson2015-2", "psm");
  p.recipe.reference.chart = "file";
  p.recipe.reference.data_digest = bytes_digest("user reference");
  const Characterisation c = characterise(p.recipe, p.training);
  const SharePayload back = decode_share_payload(encode_share_payload(share_payload(c, p.training)));
  CHECK(back.reference_XYZ == p.training.reference_XYZ);
  CHECK(reproduce_share(back).verdict == "reproduced");
}

TEST_CASE("a recipe with several chart images travels in a link, its union's reference inline", "[share]") {
  const Planted p = planted();
  Recipe r = p.recipe;
  for (const char* name : {"a.dng", "b.dng"}) {
    RecipeImage e;
    e.name = name;
    e.reference = r.reference;
    e.sampling.layout.chart = "cc24";
    r.images.push_back(e);
  }
  TrainingSet second = p.training;
  second.camera_RGB *= 1.01;  // another shot: each colour once, the mean of both
  const TrainingSet u = training_union(r, {{"a.dng", p.training}, {"b.dng", second}});
  const Characterisation c = characterise(r, u);
  const SharePayload back = decode_share_payload(encode_share_payload(share_payload(c, u)));
  CHECK(back.recipe.images.size() == 2);
  CHECK(back.labels == u.labels);
  CHECK(back.reference_XYZ == u.reference_XYZ);
  CHECK(reproduce_share(back).verdict == "reproduced");
}

TEST_CASE("damaged links are refused with their codes", "[share]") {
  const std::string payload = payload_of(planted());
  const std::size_t dot1 = payload.find('.'), dot2 = payload.rfind('.');
  SECTION("a changed character") {
    for (std::size_t at : {dot1 + 5, dot1 + (dot2 - dot1) / 2, dot2 - 2, dot2 + 3}) {
      std::string t = payload;
      t[at] = t[at] == 'A' ? 'B' : 'A';
      require_code([&] { decode_share_payload(t); }, ErrorCode::ParseError);
    }
  }
  SECTION("cut anywhere") {
    for (std::size_t n : {std::size_t(0), std::size_t(1), std::size_t(2), dot1 + 40, dot2 - 1, dot2 + 1, payload.size() - 1})
      require_code([&] { decode_share_payload(payload.substr(0, n)); }, ErrorCode::ParseError);
  }
  SECTION("a decompression bomb stops at the cap") {
    const std::string bomb(64u << 20, '[');
    const std::string t = "1." + base64url_encode(deflate_raw(bomb)) + ".AAAAAAAAAAAAAAAA";
    require_code([&] { decode_share_payload(t); }, ErrorCode::LimitExceeded);
    // Version 2 checks the compressed bytes first: a bomb needs a valid check to be inflated at all.
    const std::string data = deflate_raw(bomb, share_link_dictionary());
    Sha256 h;
    h.update(data);
    const auto sum = h.digest();
    const std::string checked = base64url_encode(std::string(reinterpret_cast<const char*>(sum.data()), 12));
    require_code([&] { decode_share_payload("2." + base64url_encode(data) + ".AAAAAAAAAAAAAAAA"); }, ErrorCode::ParseError);
    require_code([&] { decode_share_payload("2." + base64url_encode(data) + "." + checked); }, ErrorCode::LimitExceeded);
  }
  SECTION("a future version, outside and inside") {
    require_code([&] { decode_share_payload("3" + payload.substr(1)); }, ErrorCode::ProfileVersion);
    // Inside: a version 1 link's JSON document says "version": 2 (a document version never written).
    const std::string v1 = encode_share_payload_v1(decode_share_payload(payload));
    const std::size_t a = v1.find('.'), b = v1.rfind('.');
    std::string text = inflate_raw(base64url_decode(v1.substr(a + 1, b - a - 1), "t"), 1u << 20, "t");
    const auto at = text.find("\"version\":1");
    REQUIRE(at != std::string::npos);
    text.replace(at, 11, "\"version\":2");
    Sha256 h;
    h.update(text);
    const auto sum = h.digest();
    const std::string t = "1." + base64url_encode(deflate_raw(text)) + "." +
                          base64url_encode(std::string(reinterpret_cast<const char*>(sum.data()), 12));
    require_code([&] { decode_share_payload(t); }, ErrorCode::ProfileVersion);
  }
  SECTION("not a link") {
    require_code([] { decode_share_payload("http://example.org/#foo=1"); }, ErrorCode::ParseError);
    require_code([] { decode_share_payload("hello"); }, ErrorCode::ParseError);
    require_code([] { decode_share_payload(std::string(kMaxLinkChars + 1, 'A')); }, ErrorCode::LimitExceeded);
  }
}

TEST_CASE("project files round-trip with their images and refuse damage", "[share]") {
  const Planted p = planted();
  Project project;
  project.payload = share_payload(characterise(p.recipe, p.training), p.training);
  project.images = {{"chart.dng", {0, 1, 2, 'r', 'a', 'w'}}, {"flat.dng", {'f', 'l', 'a', 't'}}};
  project.session.set("step", "fit");
  const std::string bytes = project_to_bytes(project);
  CHECK(is_project_file(bytes));
  const Project back = project_from_bytes(bytes);
  REQUIRE(back.images.size() == 2);
  CHECK(back.images[0].bytes == project.images[0].bytes);
  CHECK(back.images[1].name == "flat.dng");
  CHECK(back.session.at("step").as_string() == "fit");
  CHECK(reproduce_share(back.payload).verdict == "reproduced");
  std::string damaged = bytes;
  damaged[damaged.size() - 3] ^= 1;  // an image byte
  require_code([&] { project_from_bytes(damaged); }, ErrorCode::ParseError);
  require_code([&] { project_from_bytes(bytes.substr(0, bytes.size() - 1)); }, ErrorCode::ParseError);
  require_code([&] { project_from_bytes(bytes.substr(0, 40)); }, ErrorCode::ParseError);
  require_code([&] { project_from_bytes("TRISTIM-PROJECT 2\n0\n"); }, ErrorCode::ProfileVersion);
  require_code([&] { project_from_bytes("PK\3\4"); }, ErrorCode::ParseError);
}

TEST_CASE("an absolute recipe of per-patch stimuli reproduces from its link", "[share][absolute]") {
  AbsoluteExampleOptions small;
  small.cell = 8;  // the frames are not used: small cells keep the example quick
  const AbsoluteExample ex = make_absolute_example(small);
  AbsoluteRecipe recipe;
  recipe.inputs.stimuli = read_absolute_stimuli(ex.stimuli_csv, "example stimuli");
  recipe.options.saturation = ex.sensor.saturation;
  recipe.options.noise_floor = ex.sensor.noise_floor;
  const std::string payload = share_absolute_payload(recipe);
  const SharePayload back = decode_share_payload(payload);
  CHECK(back.kind == "absolute");
  CHECK(back.absolute.inputs.stimuli.size() == recipe.inputs.stimuli.size());
  const Reproduction r = reproduce_share(back);
  CHECK(r.verdict == "reproduced");
  CHECK(r.expected.text.find("coefficients ") != std::string::npos);
  // A recipe naming frames cannot travel in a link.
  AbsoluteRecipe framed = recipe;
  framed.inputs.lens_cap = {"cap.dng"};
  require_code([&] { share_payload(AbsoluteCharacterisation{complete_absolute_recipe(framed), {}, {}, {}, {}}); },
               ErrorCode::InvalidArgument);
}

#ifndef __EMSCRIPTEN__
TEST_CASE("tristim reproduce exits 0 reproduced, 1 differs, 2 for a bad link", "[share][cli]") {
  using tristim::test::run_shell;
  using tristim::test::spit;
  const Planted p = planted();
  const Characterisation c = characterise(p.recipe, p.training);
  SharePayload s = share_payload(c, p.training);
  const std::string dir = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp");
  const std::string good = dir + "/tristim-share-good.txt", other = dir + "/tristim-share-differs.txt",
                    bad = dir + "/tristim-share-bad.txt";
  spit(good, share_link("http://127.0.0.1:8080/", encode_share_payload(s)));
  s.camera_RGB(0, 0) *= 1.02;
  spit(other, encode_share_payload(s));
  spit(bad, "3" + encode_share_payload(s).substr(1));
  const std::string cli = TRISTIM_CLI;
  auto status = [&](const std::string& args) {
    const std::string out = run_shell("'" + cli + "' " + args + " > /dev/null 2>&1; echo $?");
    return std::stoi(out);
  };
  CHECK(status("reproduce " + good) == 0);
  CHECK(run_shell("'" + cli + "' reproduce --json " + good).find("\"verdict\": \"reproduced\"") != std::string::npos);
  CHECK(status("reproduce " + other) == 1);
  const std::string differs = run_shell("'" + cli + "' reproduce --json " + other + "; true");
  CHECK(differs.find("\"verdict\": \"differs\"") != std::string::npos);
  CHECK(differs.find("\"differences\"") != std::string::npos);
  CHECK(status("reproduce " + bad) == 2);
  CHECK(run_shell("'" + cli + "' reproduce " + bad + " 2>&1; true").find("error PROFILE_VERSION:") != std::string::npos);
  for (const auto& f : {good, other, bad}) std::remove(f.c_str());
}
#endif

TEST_CASE("a profile holds its training patches, exactly, and they give its results again", "[share][profile]") {
  const Planted p = planted("Finlayson2015-2", "psm");
  const Characterisation c = characterise(p.recipe, p.training);
  REQUIRE(c.profile.has_training_data);
  const Profile q = profile_from_json(profile_to_json(c.profile));
  REQUIRE(q.has_training_data);
  CHECK(q.training_labels == c.profile.training_labels);
  CHECK((q.training_camera_RGB.array() == p.training.camera_RGB.array()).all());
  CHECK((q.training_reference_XYZ.array() == p.training.reference_XYZ.array()).all());
  // A row missing or a label too many: PROFILE_INVALID.
  std::string text = profile_to_json(c.profile);
  const size_t at = text.find("\"labels\": [");
  REQUIRE(at != std::string::npos);
  text.insert(at + 11, "\"extra\", ");
  require_code([&] { profile_from_json(text); }, ErrorCode::ProfileInvalid);
}

#ifndef __EMSCRIPTEN__
TEST_CASE("tristim share --profile p.json alone makes a link that reproduces, and altered patches are refused", "[share][cli]") {
  using tristim::test::run_shell;
  using tristim::test::spit;
  const Planted p = planted("Finlayson2015-2", "psm");
  const Characterisation c = characterise(p.recipe, p.training);
  const std::string dir = std::string(std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp");
  const std::string profile = dir + "/tristim-share-profile.json", altered = dir + "/tristim-share-altered.json";
  spit(profile, profile_to_json(c.profile));
  Profile changed = c.profile;
  changed.training_camera_RGB(3, 1) *= 1.01;
  spit(altered, profile_to_json(changed));
  const std::string cli = "'" + std::string(TRISTIM_CLI) + "'";
  const std::string link = run_shell(cli + " share --profile " + profile);
  REQUIRE(link.rfind("http://127.0.0.1:8080/#tristim=2.", 0) == 0);
  CHECK(run_shell(cli + " reproduce --json '" + link.substr(0, link.size() - 1) + "'").find("\"verdict\": \"reproduced\"") !=
        std::string::npos);
  CHECK(run_shell(cli + " share --profile " + altered + " 2>&1; true").find("error PATCH_MISMATCH:") != std::string::npos);
  for (const auto& f : {profile, altered}) std::remove(f.c_str());
}
#endif
