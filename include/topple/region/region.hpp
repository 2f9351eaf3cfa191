#pragma once
// The regional picture: many sites, one earthquake (issue 17; docs/method.md, "Regional joint inversion"). One header
// per concept, all included here for code that wants the whole picture:
//   geodesy.hpp           geodesic and hypocentral distances
//   fit.hpp               the joint fit of the attenuation and frequency relations (the model: eqs. R1-R3, F1-F3)
//   field.hpp             the pooled PGA field on a map (kriging) and its iso-acceleration contours
//   survey_inversion.hpp  a survey's inversion and regional fit, the front ends' one entry point (invert_survey)
//   inversion_distributed.hpp  the sites split across MPI ranks
// The writers (JSON, CSV, report page, map) are the output layer's: topple/output/region_output.hpp,
// region_report.hpp, region_map.hpp.
#include "topple/region/field.hpp"
#include "topple/region/fit.hpp"
#include "topple/region/geodesy.hpp"
#include "topple/region/inversion_distributed.hpp"
#include "topple/region/survey_inversion.hpp"
