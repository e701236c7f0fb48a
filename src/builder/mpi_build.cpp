#include "builder/mpi_build.h"

#include <mpi.h>

#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "core/error.h"
#include "core/stop.h"

namespace inet {

namespace {

constexpr int kTagReport = 1;  // worker -> coordinator: a result and a request for work
constexpr int kTagWork = 2;    // coordinator -> worker: a unit's order, or -1: stop

enum ReportKind : int64_t { kHello = 0, kDone = 1, kFailed = 2, kStopped = 3 };

/// A report's fixed part; the text (checksums or error) follows it in the message.
struct ReportHeader {
  int64_t kind = kHello;
  int64_t order = -1;
  double seconds = 0.0, setup_s = 0.0, sequences_s = 0.0;
  int64_t rss_kb = 0;
};

void sendReport(const ReportHeader& h, const std::string& text) {
  std::vector<char> buf(sizeof h + text.size());
  std::memcpy(buf.data(), &h, sizeof h);
  std::memcpy(buf.data() + sizeof h, text.data(), text.size());
  MPI_Send(buf.data(), static_cast<int>(buf.size()), MPI_BYTE, 0, kTagReport, MPI_COMM_WORLD);
}

int64_t receiveWork() {
  int64_t order = -1;
  // poll rather than block: Open MPI's blocking receive spins a core, which the renderer of
  // another rank on the same machine needs
  int flag = 0;
  MPI_Status st;
  while (true) {
    MPI_Iprobe(0, kTagWork, MPI_COMM_WORLD, &flag, &st);
    if (flag) break;
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  MPI_Recv(&order, 1, MPI_INT64_T, 0, kTagWork, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  return order;
}

void sendWork(int rank, int64_t order) {
  MPI_Send(&order, 1, MPI_INT64_T, rank, kTagWork, MPI_COMM_WORLD);
}

BuildReport coordinate(BuildFolder& folder, const BuildOptions& opt, int ranks) {
  Coordinator coordinator(folder, opt);  // the workers wait for their first unit meanwhile
  int active = ranks - 1;
  std::vector<char> buf;
  while (active > 0) {
    int flag = 0;
    MPI_Status st;
    MPI_Iprobe(MPI_ANY_SOURCE, kTagReport, MPI_COMM_WORLD, &flag, &st);
    if (!flag) {
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    int bytes = 0;
    MPI_Get_count(&st, MPI_BYTE, &bytes);
    ReportHeader h;
    buf.resize(std::max(static_cast<size_t>(bytes), sizeof h));
    MPI_Recv(buf.data(), bytes, MPI_BYTE, st.MPI_SOURCE, kTagReport, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    std::memcpy(&h, buf.data(), sizeof h);
    const int rank = st.MPI_SOURCE;
    if (h.kind != kHello && h.order >= 0) {
      UnitResult r;
      r.kind = h.kind == kDone     ? UnitResult::Kind::Done
               : h.kind == kFailed ? UnitResult::Kind::Failed
                                   : UnitResult::Kind::Stopped;
      r.seconds = h.seconds;
      r.setup_s = h.setup_s;
      r.sequences_s = h.sequences_s;
      r.rss_kb = h.rss_kb;
      r.text.assign(buf.data() + sizeof h, static_cast<size_t>(bytes) - sizeof h);
      coordinator.record(h.order, rank, r);
    }
    // a rank that was stopped leaves; the others get work while there is some
    const std::optional<int64_t> next = h.kind == kStopped ? std::nullopt : coordinator.claim(rank);
    sendWork(rank, next ? *next : -1);
    if (!next) --active;
  }
  return coordinator.finish(ranks - 1);
}

void work(const BuildFolder& folder) {
  sendReport(ReportHeader{}, "");
  while (true) {
    const int64_t order = receiveWork();
    if (order < 0) break;
    const UnitResult r = runUnitCaught(folder, folder.unit(order));
    ReportHeader h;
    h.kind = r.kind == UnitResult::Kind::Done     ? kDone
             : r.kind == UnitResult::Kind::Failed ? kFailed
                                                  : kStopped;
    h.order = order;
    h.seconds = r.seconds;
    h.setup_s = r.setup_s;
    h.sequences_s = r.sequences_s;
    h.rss_kb = r.rss_kb;
    sendReport(h, r.text);
  }
}

/// MPI_Init/MPI_Finalize around the build, finalising on the way out of an exception too.
struct MpiSession {
  MpiSession() {
    int provided = 0;
    MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  }
  ~MpiSession() { MPI_Finalize(); }
};

}  // namespace

bool launchedByMpi() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") != nullptr || std::getenv("PMIX_RANK") != nullptr;
}

BuildReport buildMpi(const std::filesystem::path& root, const BuildOptions& opt, int* rank_out,
                     int* ranks_out) {
  MpiSession session;
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  if (rank_out) *rank_out = rank;
  if (ranks_out) *ranks_out = ranks;
  // a bad folder is found by every rank alike (each reads the plan), so all fail together
  BuildFolder folder(root, rank == 0 ? StateAccess::Write : StateAccess::None);
  BuildReport report;
  if (ranks == 1) {
    report = buildLocal(folder, opt);
  } else if (rank == 0) {
    report = coordinate(folder, opt, ranks);
  } else {
    work(folder);  // rank 0 reports for the build
  }
  stopIfSignalled(fmt::format("(rank {} of {})", rank, ranks));
  return report;
}

}  // namespace inet
