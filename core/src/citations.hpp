// The works the method tables cite, each written once. Every table row's `reference`
// (methods.hpp; ModelInfo::reference) that cites one of these starts from its constant here, so
// the CLI's --help and `tristim models`, the page's pickers and its surface and linearisation
// steps show one citation per work, from the tables. In full:
//
//   Abed2013       F. M. Abed, R. S. Berns, K. Masaoka, "Geometry-Independent Target-Based Camera
//                  Colorimetric Characterization", J. Imaging Sci. Technol. 57(5) 050503, 2013.
//   Guarnera2018   G. C. Guarnera, S. Bianco, R. Schettini, "Turning a Digital Camera into an
//                  Absolute 2D Tele-Colorimeter", Computer Graphics Forum, 2018.
//   Shen2008       H.-L. Shen, J. H. Xin, D.-X. Yang, D.-W. Lou, "Estimation of Optoelectronic
//                  Conversion Functions of Imaging Devices Without Using Gray Samples", Color Res.
//                  Appl. 33(2) 135-141, 2008.
//   Finlayson2015  G. D. Finlayson, M. Mackiewicz, A. Hurlbert, "Color Correction Using
//                  Root-Polynomial Regression", IEEE Trans. Image Process. 24(5) 1460-1470, 2015.
//   Cheung2004     V. Cheung, S. Westland, D. Connah, C. Ripamonti, "A comparative study of the
//                  characterisation of colour cameras by means of neural networks and polynomial
//                  transforms", Coloration Technol. 120(1) 19-25, 2004.
#pragma once

namespace tristim::citation {

// Authors, year and where it appeared; a row appends the equations it implements.
constexpr const char kAbed2013[] = "Abed, Berns & Masaoka 2013, J. Imaging Sci. Technol. 57(5) 050503";
constexpr const char kGuarnera2018[] = "Guarnera, Bianco & Schettini 2018, Computer Graphics Forum";
constexpr const char kShen2008[] = "Shen, Xin, Yang & Lou 2008, Color Res. Appl. 33(2) 135-141";
constexpr const char kFinlayson2015[] = "Finlayson, Mackiewicz & Hurlbert 2015, IEEE Trans. Image Process. 24(5) 1460-1470";
constexpr const char kCheung2004[] = "Cheung, Westland, Connah & Ripamonti 2004, Coloration Technol. 120(1) 19-25";

}  // namespace tristim::citation
