// CLI helpers shared by the model commands (patch_args.cpp).
#pragma once
#include <string>
#include <vector>

#include "cli.hpp"
#include "tristim/characterisation/fit.hpp"
#include "tristim/evaluation/evaluation.hpp"
#include "tristim/profile/characterise.hpp"

namespace tristim::cli {

/// --key as D50, D65 or X,Y,Z (positive); `fallback` when absent.
Vec3 parse_white(const Args& args, const std::string& key, const Vec3& fallback);
/// "a, b,c" -> {"a","b","c"} (blanks trimmed, empty items dropped).
std::vector<std::string> split_list(const std::string& s);
std::string lower(std::string s);

/// Camera RGB and reference XYZ paired by patch id.
struct PatchData {
  std::vector<std::string> ids;     // keys (normalise_patch_id): for pairing, lookups and digests
  std::vector<std::string> labels;  // the same patches as the RGB file spells them: for outputs
  PatchMatrix rgb, xyz;
  /// Reference patches with no RGB (load_pairs with `subset`), as the reference file spells them.
  std::vector<std::string> without_rgb;
};
PatchMatrix to_matrix(const std::vector<Vec3>& v);
/// Reads both tables (CSV or CGATS) and pairs them strictly by id: every patch of one file must
/// be in the other (PatchMismatch). Reference L*a*b* is converted with ref_white. Labels: the
/// RGB file's own spelling of each id ("A01" paired with the reference's "A1" stays "A01").
/// `subset`: the RGB file may lack some of the reference's patches (a chart cut by the frame:
/// `tristim sample` writes only the visible ones) — every RGB patch must still be in the
/// reference; the pairs are the patches of both and PatchData::without_rgb lists the others.
PatchData load_pairs(const std::string& rgb_path, const std::string& xyz_path, const Vec3& ref_white,
                     bool subset = false);
/// Every --rgb with the --xyz at the same position (issue 48: several charts in one fit). One pair:
/// load_pairs of the two. Several: the union of their patches in the order given, each chart's ids
/// prefixed with its number ("2:A1"), so ids stay distinct and say which chart they come from; a
/// fit on them is the fit on one table holding the same rows. InvalidArgument when the counts of
/// --rgb and --xyz differ. `subset`: as above, for each pair (without_rgb prefixed like the ids).
PatchData load_pairs(const Args& args, const Vec3& ref_white, bool subset = false);
/// "tristim <command>: 3 reference patches have no RGB (A1, B3, D6): <done> on the 21 others\n"
/// for load_pairs's `without_rgb` with `subset` ("" when every reference patch has RGB).
std::string without_rgb_note(const std::string& command, const std::string& done, const PatchData& d);
/// The bytes of every file of `paths`, one after the other (the data digest of several --xyz; one
/// file: its bytes).
std::string read_files(const std::vector<std::string>& paths);
/// Per chart (several --rgb only; "" otherwise): "tristim: chart k (path): n patches, training
/// mean/max dE00 …, leave-one-out mean/max dE00 …" lines of the evaluation `ev`, whose rows are
/// `labels` (load_pairs's "k:id"; rows of no chart number are left out).
std::string per_chart_figures(const Args& args, const std::vector<std::string>& labels, const ModelEvaluation& ev);
/// Per chart of a recipe with images (profile/characterise.hpp's chart_figures): "tristim: chart k
/// (name): n patches, training mean/max dE00 …, leave-one-out mean/max dE00 …, held out (fitted on
/// the other charts) mean/max dE00 …" lines ("" for none).
std::string chart_figures_text(const std::vector<ChartFigures>& charts);
/// The same for the best row of a compare table (its first that fitted), evaluated again on d with
/// `options` and that row's objective, under a heading naming the row; "" for one chart.
std::string per_chart_compare(const Args& args, const PatchData& d, const FitOptions& options,
                              const std::vector<CompareRow>& rows, int white_index);
/// Row of `id` in ids (normalised; with several charts an id without a chart number is chart 1's);
/// Error(UnknownId) naming --white otherwise.
int patch_index(const std::vector<std::string>& ids, const std::string& id);
/// --help of fit and compare: the models, objectives and linearisations, each with its table's reference.
std::string fit_methods_help();
/// FitOptions from --objective, --lab-white, --white and the --psm-* / --de-* flags.
FitOptions fit_options(const Args& args, const PatchData& d, int& white_index);

void write_bytes(const std::string& path, const void* data, size_t n);
/// Lower-case extension without the dot ("" when none).
std::string ext_of(const std::string& path);
/// Fixed-point text; "-" for non-finite values.
std::string fmt(double v, int prec = 3);

}  // namespace tristim::cli
