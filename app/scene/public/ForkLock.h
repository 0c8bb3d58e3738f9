// Every read of a file through a parsing library forks a child, after ending TBB's worker threads
// (IsolatedRead.cxx): a child forked while another thread runs TBB's parallel loops would wait
// forever for workers it does not have, and TBB's threads cannot be ended while a loop runs. A
// process that reads fields on one thread while another thread runs such loops (the viewer,
// which reads the next time step in the background while its window renders) holds this lock
// around those loops; the read takes it around its fork.
#ifndef cloudvis_ForkLock_h
#define cloudvis_ForkLock_h

#include <mutex>

namespace cloudvis
{

std::mutex& ForkLock();

} // namespace cloudvis

#endif
