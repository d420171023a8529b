// A method's citation has one place: its row in the engine's tables (MethodInfo::reference,
// ModelInfo::reference, built from core/src/citations.hpp). Every row has one; a row that cites a
// work cites it in full (authors, year, venue); the CLI's --help prints the rows' references; the
// page shows them from the catalog call and hard-codes no citation of its own.
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#ifndef __EMSCRIPTEN__
#include <filesystem>
#endif

#include "test_support.hpp"
#include "tristim/capture/calibration.hpp"
#include "tristim/characterisation/models.hpp"
#include "tristim/characterisation/objectives.hpp"
#include "tristim/linearisation/linearisation.hpp"
#include "tristim/methods.hpp"
#include "tristim/surface/surface.hpp"

using namespace tristim;

namespace {

struct Row {
  std::string table, id, reference;
};

std::vector<Row> all_rows() {
  std::vector<Row> rows;
  for (const auto& m : model_table()) rows.push_back({"models", m.id, m.reference});
  for (const auto& o : objective_table()) rows.push_back({"objectives", o.info.id, o.info.reference});
  for (const auto& l : linearisation_table()) rows.push_back({"linearisation", l.info.id, l.info.reference});
  for (const auto& s : surface_table()) rows.push_back({"surface", s.info.id, s.info.reference});
  for (const auto& f : flat_field_methods()) rows.push_back({"flat field", f.id, f.reference});
  return rows;
}

bool contains(const std::string& s, const std::string& part) { return s.find(part) != std::string::npos; }

// Each cited work, by the author the rows name first, and its venue as citations.hpp writes it.
struct Work {
  const char* author;
  const char* full;  // authors and year as cited
  const char* venue;
};
const Work kWorks[] = {
    {"Abed", "Abed, Berns & Masaoka 2013", "J. Imaging Sci. Technol. 57(5) 050503"},
    {"Guarnera", "Guarnera, Bianco & Schettini 2018", "Computer Graphics Forum"},
    {"Shen", "Shen, Xin, Yang & Lou 2008", "Color Res. Appl. 33(2) 135-141"},
    {"Finlayson", "Finlayson, Mackiewicz & Hurlbert 2015", "IEEE Trans. Image Process. 24(5) 1460-1470"},
    {"Cheung", "Cheung, Westland, Connah & Ripamonti 2004", "Coloration Technol. 120(1) 19-25"},
};

}  // namespace

TEST_CASE("every method table row has a reference", "[methods][references]") {
  const auto rows = all_rows();
  CHECK(rows.size() > 40);
  for (const auto& r : rows) {
    INFO(r.table << " row " << r.id);
    CHECK(!r.reference.empty());
  }
}

TEST_CASE("a row that cites a work cites it in full, with the right venue", "[methods][references]") {
  for (const auto& r : all_rows()) {
    INFO(r.table << " row " << r.id << ": " << r.reference);
    CHECK(!contains(r.reference, "Color Res. Appl. 39"));
    for (const Work& w : kWorks) {
      if (!contains(r.reference, w.author)) continue;
      // Every mention of the author is the full citation (a short "Abed 2013" would be a second spelling).
      size_t mentions = 0, full = 0;
      for (size_t at = r.reference.find(w.author); at != std::string::npos; at = r.reference.find(w.author, at + 1)) ++mentions;
      for (size_t at = r.reference.find(w.full); at != std::string::npos; at = r.reference.find(w.full, at + 1)) {
        ++full;
        CHECK(r.reference.compare(at + std::string(w.full).size(), std::string(w.venue).size() + 2,
                                  std::string(", ") + w.venue) == 0);
      }
      CHECK(full == mentions);
    }
  }
  // The surface corrections are Abed et al.'s, the Shen2008 rows Shen et al.'s.
  for (const auto& s : surface_table()) CHECK(contains(s.info.reference, "J. Imaging Sci. Technol. 57(5) 050503"));
  CHECK(contains(linearisation_method("Shen2008").info.reference, "Color Res. Appl. 33(2) 135-141"));
  CHECK(contains(model_info("Shen2008").reference, "Color Res. Appl. 33(2) 135-141"));
}

#ifndef __EMSCRIPTEN__
TEST_CASE("the page hard-codes no citation: it shows the tables' references", "[methods][references][web]") {
  // Venues as the tables write them, and the wrong one the surface step once had: any of these in
  // the page's code would be a second place for a citation.
  const std::vector<std::string> banned = {"Color Res. Appl. 39", "Color Res. Appl.", "J. Imaging Sci. Technol.",
                                           "Computer Graphics Forum", "IEEE Trans. Image Process.", "Coloration Technol."};
  size_t scanned = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(std::string(TRISTIM_SOURCE_DIR) + "/web")) {
    const std::string ext = e.path().extension().string();
    if (!e.is_regular_file() || (ext != ".js" && ext != ".html")) continue;
    std::ifstream in(e.path(), std::ios::binary);
    std::ostringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    ++scanned;
    for (const auto& b : banned) {
      INFO(e.path().string() << " contains \"" << b << "\"");
      CHECK(!contains(text, b));
    }
  }
  CHECK(scanned > 20);
}
#endif

#if !defined(__EMSCRIPTEN__) && defined(TRISTIM_CLI)
namespace {
std::string help(const std::string& command) {
  FILE* f = popen((std::string(TRISTIM_CLI) + " " + command + " --help").c_str(), "r");
  REQUIRE(f != nullptr);
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = fread(buf, 1, sizeof buf, f)) > 0) out.append(buf, n);
  REQUIRE(pclose(f) == 0);
  return out;
}
}  // namespace

TEST_CASE("cli: --help prints each method's reference from its table", "[cli][methods][references]") {
  const std::string surface = help("surface"), linearise = help("linearise"), fit = help("fit"), compare = help("compare"),
                    spectral = help("spectral");
  for (const auto& s : surface_table()) {
    INFO(s.info.id);
    CHECK(contains(surface, s.info.id + ": " + s.info.label + " — " + s.info.reference));
  }
  for (const auto& l : linearisation_table()) {
    INFO(l.info.id);
    CHECK(contains(linearise, l.info.id + ": " + l.info.label + " — " + l.info.reference));
    CHECK(contains(spectral, l.info.reference));
    CHECK(contains(fit, l.info.reference));
  }
  for (const auto& o : objective_table()) {
    INFO(o.info.id);
    CHECK(contains(fit, o.info.id + ": " + o.info.label + " — " + o.info.reference));
    CHECK(contains(compare, o.info.reference));
  }
  for (const auto& m : model_table()) {
    INFO(m.id);
    CHECK(contains(fit, m.id + ": " + m.label));
    CHECK(contains(fit, m.reference));
    CHECK(contains(compare, m.reference));
  }
  CHECK(!contains(surface + linearise + fit, "Color Res. Appl. 39"));
}
#endif
