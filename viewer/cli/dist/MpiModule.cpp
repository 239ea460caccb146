// csgray_mpi.so: CsgrayMpiCalls on Open MPI's C bindings. Loaded by Ranks (dlopen) only when
// mpirun or srun started csgray.
#include <mpi.h>

#include <algorithm>

#include "viewer/cli/dist/MpiCalls.h"

namespace {

int init(int* rank, int* size) {
    // Only the main thread calls MPI (TaskFarm's serving loops and the collectives) while
    // worker threads render: FUNNELED is all csgray needs.
    int provided = 0;
    if (MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) return 1;
    MPI_Comm_rank(MPI_COMM_WORLD, rank);
    MPI_Comm_size(MPI_COMM_WORLD, size);
    return 0;
}

void finalize() {
    int finalized = 0;
    MPI_Finalized(&finalized);
    if (!finalized) MPI_Finalize();
}

int allMin(int value) {
    int all = 0;
    MPI_Allreduce(&value, &all, 1, MPI_INT, MPI_MIN, MPI_COMM_WORLD);
    return all;
}

void sumToRoot(unsigned long long* values, int n, int isRoot) {
    if (isRoot)
        MPI_Reduce(MPI_IN_PLACE, values, n, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
    else
        MPI_Reduce(values, nullptr, n, MPI_UNSIGNED_LONG_LONG, MPI_SUM, 0, MPI_COMM_WORLD);
}

void abortJob(int code) {
    MPI_Abort(MPI_COMM_WORLD, code);
}

void fill(const MPI_Status& status, CsgrayMpiMessage* message) {
    message->source = status.MPI_SOURCE;
    message->tag = status.MPI_TAG;
    MPI_Get_count(&status, MPI_BYTE, &message->bytes);
}

int poll(int source, int tag, CsgrayMpiMessage* message) {
    int arrived = 0;
    MPI_Status status;
    MPI_Iprobe(source < 0 ? MPI_ANY_SOURCE : source, tag, MPI_COMM_WORLD, &arrived, &status);
    if (arrived) fill(status, message);
    return arrived;
}

void probe(int source, int tag, CsgrayMpiMessage* message) {
    MPI_Status status;
    MPI_Probe(source < 0 ? MPI_ANY_SOURCE : source, tag, MPI_COMM_WORLD, &status);
    fill(status, message);
}

void receive(const CsgrayMpiMessage* message, void* buffer) {
    MPI_Recv(buffer, message->bytes, MPI_BYTE, message->source, message->tag, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
}

void send(const void* data, int bytes, int to, int tag) {
    MPI_Send(data, bytes, MPI_BYTE, to, tag, MPI_COMM_WORLD);
}

void* startSend(const void* data, int bytes, int to, int tag) {
    auto* request = new MPI_Request;
    MPI_Isend(data, bytes, MPI_BYTE, to, tag, MPI_COMM_WORLD, request);
    return request;
}

void wait(void* handle) {
    if (!handle) return;
    auto* request = static_cast<MPI_Request*>(handle);
    MPI_Wait(request, MPI_STATUS_IGNORE);
    delete request;
}

void broadcast(void* bytes, long long n) {
    // MPI counts are ints: pieces of at most 2^30 bytes.
    constexpr long long kPiece = 1LL << 30;
    for (long long done = 0; done < n; done += kPiece)
        MPI_Bcast(static_cast<char*>(bytes) + done, int(std::min(kPiece, n - done)), MPI_BYTE, 0,
                  MPI_COMM_WORLD);
}

constexpr CsgrayMpiCalls kCalls = {init,  finalize, allMin, sumToRoot, abortJob, poll,
                                   probe, receive,  send,   startSend, wait,     broadcast};

}  // namespace

extern "C" __attribute__((visibility("default"))) const CsgrayMpiCalls* csgrayMpiCalls() {
    return &kCalls;
}
