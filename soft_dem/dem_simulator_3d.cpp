// The 3D instances of the soft DEM (dem_simulator_impl.hpp); the 2D ones compile beside
// them in dem_simulator_2d.cpp.
#include "soft_dem/dem_simulator_impl.hpp"

namespace granjet::dem {

// The linear law's instances, for tests and benchmarks that build a simulator directly; other
// laws are instantiated by the factory.
template class DemSimulator<3, LinearSpringDashpot<3, false>, false>;
template class DemSimulator<3, LinearSpringDashpot<3, false>, true>;
template class DemSimulator<3, LinearSpringDashpot<3, true>, false>;
template class DemSimulator<3, LinearSpringDashpot<3, true>, true>;
// Rolling resistance on the linear law, monodisperse, for tests that set the grains' spins.
template class DemSimulator<3, Rolling<LinearSpringDashpot<3, true>>, true>;
template std::unique_ptr<Simulator<3>> make_dem_simulator<3>(const Scene&, const RankTeam&);

}  // namespace granjet::dem
