// Training stimuli CSV (format in tristim/absolute/stimuli_file.hpp).
#include "tristim/absolute/stimuli_file.hpp"

#include <cmath>
#include <cstdio>

#include "tristim/error.hpp"
#include "tristim/io/patch_files.hpp"

namespace tristim {

bool equal_tristimulus(const Vec3& v) {
  return std::fabs(v[0] - v[1]) <= 0.02 * v[1] && std::fabs(v[2] - v[1]) <= 0.02 * v[1];
}

std::vector<StimulusRow> read_stimuli_csv(std::string_view text, const std::string& path) {
  const TextTable t = parse_delimited(text, path);
  auto col = [&](const char* name) {
    for (size_t k = 0; k < t.header.size(); ++k)
      if (t.header[k] == name) return static_cast<int>(k);
    return -1;
  };
  const int id = col("id"), set = col("set"), ex = col("exposure_s"), fn = col("f_number"), iso = col("iso");
  const int file = col("file"), x = col("x"), y = col("y"), w = col("w"), h = col("h");
  const int R = col("R"), G = col("G"), B = col("B"), fall = col("falloff"), X = col("X"), Y = col("Y"), Z = col("Z");
  if (X < 0 || Y < 0 || Z < 0) throw Error(ErrorCode::MissingColumn, path + ": the measured X, Y, Z (cd/m²) columns are needed");
  if (file < 0 && (R < 0 || G < 0 || B < 0))
    throw Error(ErrorCode::MissingColumn, path + ": give per-patch R, G, B columns or a file column with a region x, y, w, h");
  std::vector<StimulusRow> rows;
  for (size_t r = 0; r < t.rows.size(); ++r) {
    const auto& row = t.rows[r];
    const int line = t.lines[r];
    auto num = [&](int c, const char* name) { return parse_cell(row[c], path, line, name); };
    auto opt = [&](int c, const char* name, double fallback) { return c >= 0 && !row[c].empty() ? num(c, name) : fallback; };
    auto pixel = [&](int c, const char* name) {  // a region coordinate: a number an int holds
      const double v = num(c, name);
      if (!(std::fabs(v) < 2147483647.0))
        throw Error(ErrorCode::InvalidArgument, path + ", line " + std::to_string(line) + ": " + name + " is not a pixel position");
      return static_cast<int>(v);
    };
    StimulusRow s;
    s.line = line;
    s.stimulus.id = id >= 0 ? row[id] : std::to_string(r + 1);
    s.stimulus.XYZ = Vec3(num(X, "X"), num(Y, "Y"), num(Z, "Z"));
    s.stimulus.exposure = {opt(ex, "exposure_s", 0), opt(fn, "f_number", 0), opt(iso, "iso", 0)};
    if (set >= 0 && !row[set].empty()) {
      const std::string& v = row[set];
      if (v != "luminance" && v != "oecf" && v != "colour" && v != "color")
        throw Error(ErrorCode::InvalidArgument, path + ", line " + std::to_string(line) + ": set is luminance or colour, not '" + v + "'");
      s.stimulus.luminance_set = v == "luminance" || v == "oecf";
    } else {
      s.stimulus.luminance_set = equal_tristimulus(s.stimulus.XYZ);
    }
    if (file >= 0 && !row[file].empty()) {
      if (x < 0 || y < 0 || w < 0 || h < 0) throw Error(ErrorCode::MissingColumn, path + ": a file row needs x, y, w, h");
      s.file = row[file];
      s.x = pixel(x, "x");
      s.y = pixel(y, "y");
      s.w = pixel(w, "w");
      s.h = pixel(h, "h");
    } else {
      if (R < 0 || G < 0 || B < 0)
        throw Error(ErrorCode::MissingColumn, path + ", line " + std::to_string(line) + ": no file and no R, G, B");
      s.stimulus.raw_RGB = Vec3(num(R, "R"), num(G, "G"), num(B, "B"));
      s.stimulus.falloff = opt(fall, "falloff", 1.0);
      if (!(s.stimulus.exposure.exposure_s > 0) || !(s.stimulus.exposure.f_number > 0))
        throw Error(ErrorCode::MissingMetadata, path + ", line " + std::to_string(line) +
                                                    ": a per-patch row needs exposure_s and f_number");
    }
    rows.push_back(s);
  }
  if (rows.empty()) throw Error(ErrorCode::EmptyFile, path + ": no stimuli");
  return rows;
}

std::string stimuli_to_csv(const std::vector<TrainingStimulus>& stimuli) {
  std::string out = "id,set,exposure_s,f_number,iso,R,G,B,falloff,X,Y,Z\n";
  char buf[64];
  auto num = [&](double v) {
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  for (const auto& s : stimuli) {
    out += s.id + "," + (s.luminance_set ? "luminance" : "colour") + "," + num(s.exposure.exposure_s) + "," +
           num(s.exposure.f_number) + "," + num(s.exposure.iso);
    for (int c = 0; c < 3; ++c) out += "," + num(s.raw_RGB[c]);
    out += "," + num(s.falloff);
    for (int c = 0; c < 3; ++c) out += "," + num(s.XYZ[c]);
    out += "\n";
  }
  return out;
}

}  // namespace tristim
