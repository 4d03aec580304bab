// The 2D instances of the soft DEM (dem_simulator_impl.hpp); the 3D ones compile beside
// them in dem_simulator_3d.cpp.
#include "soft_dem/dem_simulator_impl.hpp"

namespace granjet::dem {

// The linear law's instances, for tests and benchmarks that build a simulator directly; other
// laws are instantiated by the factory.
template class DemSimulator<2, LinearSpringDashpot<2, false>, false>;
template class DemSimulator<2, LinearSpringDashpot<2, false>, true>;
template class DemSimulator<2, LinearSpringDashpot<2, true>, false>;
template class DemSimulator<2, LinearSpringDashpot<2, true>, true>;
// Rolling resistance on the linear law, monodisperse, for tests that set the grains' spins.
template class DemSimulator<2, Rolling<LinearSpringDashpot<2, true>>, true>;
template std::unique_ptr<Simulator<2>> make_dem_simulator<2>(const Scene&, const RankTeam&);

}  // namespace granjet::dem
