// Declarations: ACES Input Transforms (profile/idt.hpp, profile/clf.hpp) for the page's Export step:
// the IDT of a built-in camera, of sensitivities uploaded as CSV or of the chart's patches as the files `tristim idt` writes (CLF,
// plain 3x3, JSON), and the engine's strict CLF reader, whose result crosses as clf_json's object.
#include "tristim/profile/clf.hpp"
#include "types.hpp"

using namespace tristim;
using emscripten::val;
using wasm::def;

template <>
struct tristim::wasm::Conv<IdtFiles> {  // {clf, matrix, json: the object of the JSON text}
  static val to(const IdtFiles& f) {
    val o = val::object();
    o.set("clf", f.clf);
    o.set("matrix", f.matrix);
    o.set("json", val::global("JSON").call<val>("parse", val(f.json)));
    return o;
  }
  static IdtFiles from(const val&) { wasm::refuse("IDT files are an output"); }
};
template <>
struct tristim::wasm::Conv<std::pair<std::string, std::string>> {  // [key, value]
  static val to(const std::pair<std::string, std::string>& p) { return Conv<std::vector<std::string>>::to({p.first, p.second}); }
  static std::pair<std::string, std::string> from(const val& v) {
    const auto s = Conv<std::vector<std::string>>::from(v);
    if (s.size() != 2) throw Error(ErrorCode::InvalidArgument, "an Info entry is [name, text]");
    return {s[0], s[1]};
  }
};
template <>  // the object clf_json is
struct tristim::wasm::Conv<ClfDocument> : wasm::JsonOutput<ClfDocument, &clf_json> {};

EMSCRIPTEN_BINDINGS(tristim_idt) {
  def<&idt_camera_files>("idtCamera");
  def<&idt_sensitivities_files>("idtSensitivities");
  def<&idt_chart_files>("idtChart");
  def<&read_clf>("readClf");
}
