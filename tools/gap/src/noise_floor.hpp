#pragma once
// The library's noise floor (engine.cpp): the scatter of drives with nothing missing from the
// model but their truck, once the nominal truck is fitted to each.
#include <string>
#include <vector>

#include "roadload/gap/engine.hpp"

namespace roadload::gap {

// The smallest gap worth explaining on a channel.
double resolution(const std::string& channel);

// Sets lib.nominal_delta from the features with each nominal parameter at its value plus one
// sigma (lib.baseline and lib.keys set).
void set_nominal_delta(ModelLibrary& lib, const std::vector<Eigen::VectorXd>& plus_sigma);

// The nominal parameters as the fit sees them: each response to one sigma, whitened by `sigma`.
std::vector<NominalColumn> nominal_columns(const ModelLibrary& lib, const Eigen::VectorXd& sigma);

// Sets lib.sigma, the held-out chi-square of the noise drives and how far the nominal fit missed
// their trucks, from their residuals against their re-simulations and the trucks they drove (each
// parameter's offset in prior sigmas).
void set_noise_floor(ModelLibrary& lib, const std::vector<Eigen::VectorXd>& residuals,
                     const std::vector<std::vector<double>>& trucks);

// Widens a fit's 90 % intervals by what the fit missed on the noise drives (a t quantile for
// their number).
void widen_by_miss(NominalFit& fit, const ModelLibrary& lib, const std::vector<NominalColumn>& columns);

}  // namespace roadload::gap
