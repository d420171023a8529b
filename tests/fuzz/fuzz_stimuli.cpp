// Training stimuli CSV of the absolute tele-colorimeter (absolute/stimuli_file.hpp
// read_stimuli_csv): per-patch rows (R, G, B, exposure) and region rows (file, x, y, w, h), as
// `tristim absolute fit --stimuli` and the page's absolute step read them. Seeds: corpus/stimuli/.
#include "fuzz_support.hpp"
#include "tristim/absolute/stimuli_file.hpp"

TRISTIM_FUZZ_TARGET({ tristim::read_stimuli_csv(input, "in.csv"); })
