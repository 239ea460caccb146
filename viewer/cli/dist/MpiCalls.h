// The MPI calls csgray makes, as a table of C functions. The table is filled by the module
// csgray_mpi.so (MpiModule.cpp, the one file that includes mpi.h and links libmpi), which
// Ranks loads with dlopen only when a launcher started the process: a plain run does not load
// libmpi at all, which would cost every start of csgray about 2 ms (bench/README.md, MPI).
#pragma once

extern "C" {

// A message that has arrived and not yet been received (what MPI_Probe tells).
struct CsgrayMpiMessage {
    int source;
    int tag;
    int bytes;
};

struct CsgrayMpiCalls {
    // MPI_Init_thread(MPI_THREAD_FUNNELED), then this process's rank and the job's size;
    // returns 0 on success.
    int (*init)(int* rank, int* size);
    void (*finalize)();
    // The minimum of value over the ranks (collective).
    int (*allMin)(int value);
    // Sums values[0, n) over the ranks into rank 0's (collective).
    void (*sumToRoot)(unsigned long long* values, int n, int isRoot);
    void (*abort)(int code);
    // Whether a message with tag from source (-1: any) is waiting; fills message if so.
    int (*poll)(int source, int tag, CsgrayMpiMessage* message);
    // Waits for such a message.
    void (*probe)(int source, int tag, CsgrayMpiMessage* message);
    // Receives a message poll or probe found into buffer (message->bytes long).
    void (*receive)(const CsgrayMpiMessage* message, void* buffer);
    void (*send)(const void* data, int bytes, int to, int tag);
    // Starts a send whose data must stay alive until wait(handle) returns (a null handle: none).
    void* (*startSend)(const void* data, int bytes, int to, int tag);
    void (*wait)(void* handle);
    // Rank 0's bytes[0, n) to every rank's (collective; n the same on every rank).
    void (*broadcast)(void* bytes, long long n);
};

// The module's one exported function.
const CsgrayMpiCalls* csgrayMpiCalls();
typedef const CsgrayMpiCalls* (*CsgrayMpiCallsFunction)();
}
