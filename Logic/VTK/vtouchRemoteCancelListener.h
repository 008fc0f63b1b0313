// The side channel of a Cancel on a pvserver (issue 19 item 1, issue 16 item 6): while the ranks
// run VesselCenterline, the client's connection to the server is busy with the update (the
// client waits for its reply and can send nothing the server would read before the run ends), so
// each rank listens for the cancel on a socket of its own; the client tells the first rank's,
// which tells the others' (forwardTo). Project rule (Docs/CLIENT-SERVER.md,
// "Cancel on a pvserver"): a TCP socket on every interface of the server machine (the pvserver
// itself listens on all of them by default), on a port the system chooses (none to configure, no
// clash between runs), announced to the client in the filter's progress text, which ParaView
// sends from the first rank to the client during the update; a connection must send the run's
// token (a random string the client set in the RemoteCancelToken property) before the newline to
// cancel, so a stray connection cannot. One thread waits in poll() with a 100 ms time-out (to see
// its stop) and reads a connection with a 1 s time-out; the socket closes when the object is
// destroyed (the run's end). A socket that cannot be opened leaves the run uncancellable, with
// the reason in error(); the run itself goes on.
#pragma once

#include <atomic>
#include <mutex>
#include <string>
#include <thread>
#include <utility>
#include <vector>

namespace vtouch
{

class RemoteCancelListener
{
public:
  /// Opens the socket and starts the thread. `token`: what a connection must send (not empty).
  explicit RemoteCancelListener(std::string token);
  /// Stops the thread (within its 100 ms time-out), joins it and closes the socket.
  ~RemoteCancelListener();
  RemoteCancelListener(const RemoteCancelListener&) = delete;
  RemoteCancelListener& operator=(const RemoteCancelListener&) = delete;

  /// Whether the socket is open (else error() says why and nobody can cancel this run).
  bool listening() const { return this->Port > 0; }
  /// The port the system chose, 0 when not listening.
  int port() const { return this->Port; }
  const std::string& error() const { return this->Error; }
  /// Set (once, never cleared) when a connection sent the token.
  const std::atomic<bool>& cancelled() const { return this->Cancelled; }

  /// The other ranks' listeners (host, port), which this one tells when it hears the token, so
  /// that every rank stops at its next local check point instead of its next exchange (project
  /// rule: a rank's local stages can run tens of seconds between exchanges). Sent at once if the
  /// token came before. A peer that cannot be reached (1 s) stops at its next exchange.
  void forwardTo(std::vector<std::pair<std::string, int>> peers);
  /// This machine's host name (what the other ranks connect to).
  static std::string hostName();

private:
  void serve();
  /// Reads one line of a connection (1 s time-out); true when it is the token.
  bool readToken(int connection) const;
  /// Sends the token to every peer not told yet.
  void forward();

  std::string Token;
  int Socket = -1;
  int Port = 0;
  std::string Error;
  std::atomic<bool> Cancelled{ false };
  std::atomic<bool> Stop{ false };
  std::mutex PeersMutex;
  std::vector<std::pair<std::string, int>> Peers;
  std::thread Thread;
};

} // namespace vtouch
