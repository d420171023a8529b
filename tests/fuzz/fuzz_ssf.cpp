// Camera spectral sensitivities CSV (simulate/virtual_camera.hpp read_ssf_csv): the SSF file the
// page's sensitivities step and `tristim absolute fit --ssf` read. Seeds: corpus/ssf/ (R/G/B,
// *_R/*_G/*_B and red/green/blue headers, three unnamed columns, a decimal comma).
#include "fuzz_support.hpp"
#include "tristim/simulate/virtual_camera.hpp"

TRISTIM_FUZZ_TARGET({ tristim::read_ssf_csv(input, "in.csv"); })
