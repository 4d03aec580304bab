#include "campaign/mpi_world.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <thread>

#ifdef GRANJET_HAS_MPI
#include <mpi.h>
#endif

namespace granjet {
namespace {

std::string this_host() {
  std::array<char, 256> name{};
  if (gethostname(name.data(), name.size() - 1) != 0) return "unknown";
  return name.data();
}

#ifdef GRANJET_HAS_MPI
constexpr int kReportTag = 1;
constexpr int kAssignTag = 2;
constexpr auto kPoll = std::chrono::milliseconds(20);

// Open MPI's blocking calls spin a core; a campaign's ranks wait long, so they wait by polling.
void wait_for(MPI_Request& request) {
  for (int done = 0; MPI_Test(&request, &done, MPI_STATUS_IGNORE), !done;)
    std::this_thread::sleep_for(kPoll);
}
#endif

}  // namespace

bool built_with_mpi() {
#ifdef GRANJET_HAS_MPI
  return true;
#else
  return false;
#endif
}

MpiWorld::MpiWorld() {
  const int launched = launched_ranks();
#ifdef GRANJET_HAS_MPI
  if (launched > 1) {
    MPI_Init(nullptr, nullptr);
    initialised_ = true;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
    MPI_Comm_size(MPI_COMM_WORLD, &size_);
  }
#else
  if (launched > 1)
    throw std::runtime_error(
        "started as one of " + std::to_string(launched) +
        " MPI ranks, but this granjet was built without MPI: every rank would run the whole "
        "campaign. Rebuild with Open MPI (libopenmpi-dev; scripts/setup.sh installs it) or use "
        "--jobs on one machine");
#endif
}

MpiWorld::~MpiWorld() {
#ifdef GRANJET_HAS_MPI
  if (!initialised_) return;
  if (std::uncaught_exceptions() > 0) MPI_Abort(MPI_COMM_WORLD, 1);
  MPI_Request barrier;
  MPI_Ibarrier(MPI_COMM_WORLD, &barrier);
  wait_for(barrier);
  MPI_Finalize();
#endif
}

std::vector<std::string> MpiWorld::hostnames() {
  const std::string mine = this_host();
#ifdef GRANJET_HAS_MPI
  if (initialised_) {
    constexpr int kWidth = 256;
    std::vector<char> all(static_cast<std::size_t>(kWidth) * size_, '\0');
    std::array<char, kWidth> own{};
    mine.copy(own.data(), kWidth - 1);
    MPI_Allgather(own.data(), kWidth, MPI_CHAR, all.data(), kWidth, MPI_CHAR, MPI_COMM_WORLD);
    std::vector<std::string> names;
    for (int r = 0; r < size_; ++r) names.emplace_back(all.data() + r * kWidth);
    return names;
  }
#endif
  return {mine};
}

std::optional<MpiWorld::Report> MpiWorld::try_receive() {
#ifdef GRANJET_HAS_MPI
  if (!initialised_) return std::nullopt;
  int waiting = 0;
  MPI_Status status;
  MPI_Iprobe(MPI_ANY_SOURCE, kReportTag, MPI_COMM_WORLD, &waiting, &status);
  if (!waiting) return std::nullopt;
  std::array<double, 3> message{};
  MPI_Recv(message.data(), 3, MPI_DOUBLE, status.MPI_SOURCE, kReportTag, MPI_COMM_WORLD,
           MPI_STATUS_IGNORE);
  return Report{static_cast<std::int64_t>(message[0]), static_cast<int>(message[1]), message[2],
                status.MPI_SOURCE};
#else
  return std::nullopt;
#endif
}

void MpiWorld::assign(int rank, std::int64_t run) {
#ifdef GRANJET_HAS_MPI
  if (!initialised_) throw std::logic_error("MpiWorld::assign without MPI");
  const double message = static_cast<double>(run);
  MPI_Send(&message, 1, MPI_DOUBLE, rank, kAssignTag, MPI_COMM_WORLD);
#else
  (void)rank;
  (void)run;
  throw std::logic_error("MpiWorld::assign without MPI");
#endif
}

std::int64_t MpiWorld::report_and_receive(const Report& report) {
#ifdef GRANJET_HAS_MPI
  if (!initialised_) throw std::logic_error("MpiWorld::report_and_receive without MPI");
  const std::array<double, 3> message{static_cast<double>(report.run),
                                      static_cast<double>(report.exit_code), report.seconds};
  MPI_Send(message.data(), 3, MPI_DOUBLE, 0, kReportTag, MPI_COMM_WORLD);
  double run = -1.0;
  MPI_Request request;
  MPI_Irecv(&run, 1, MPI_DOUBLE, 0, kAssignTag, MPI_COMM_WORLD, &request);
  wait_for(request);
  return static_cast<std::int64_t>(run);
#else
  (void)report;
  throw std::logic_error("MpiWorld::report_and_receive without MPI");
#endif
}

}  // namespace granjet
