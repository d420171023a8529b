// tristim — the DNG writer moved into the core (the colorimetry lab writes real DNGs with it);
// tests include it from here as before.
#pragma once
#include "tristim/lab/dng_writer.hpp"
