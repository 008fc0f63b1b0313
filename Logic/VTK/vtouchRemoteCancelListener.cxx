// vtouch::RemoteCancelListener: the first rank's cancel socket (see the header).
#include "vtouchRemoteCancelListener.h"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/time.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <utility>

namespace vtouch
{
namespace
{
/// The stop check's period: the thread's longest wait in poll() (project rule: the run's end
/// waits at most this long for the thread).
constexpr int kPollTimeout_ms = 100;
/// A connection that sends nothing is dropped after this (project rule: a stray connection must
/// not hold the only thread for long).
constexpr int kReadTimeout_s = 1;
/// A token line longer than this is not the token.
constexpr std::size_t kMaximumLine = 256;
} // namespace

RemoteCancelListener::RemoteCancelListener(std::string token)
  : Token(std::move(token))
{
  if (this->Token.empty() || this->Token.size() >= kMaximumLine)
  {
    this->Error = "the cancel token is empty or too long";
    return;
  }
  this->Socket = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_ANY);
  address.sin_port = 0; // the system's choice
  socklen_t length = sizeof(address);
  if (this->Socket < 0 ||
      ::bind(this->Socket, reinterpret_cast<sockaddr*>(&address), sizeof(address)) != 0 ||
      ::listen(this->Socket, 4) != 0 ||
      ::getsockname(this->Socket, reinterpret_cast<sockaddr*>(&address), &length) != 0)
  {
    this->Error = std::string("no cancel socket: ") + std::strerror(errno);
    if (this->Socket >= 0)
    {
      ::close(this->Socket);
      this->Socket = -1;
    }
    return;
  }
  this->Port = ntohs(address.sin_port);
  this->Thread = std::thread([this] { this->serve(); });
}

RemoteCancelListener::~RemoteCancelListener()
{
  this->Stop = true;
  if (this->Thread.joinable())
  {
    this->Thread.join();
  }
  if (this->Socket >= 0)
  {
    ::close(this->Socket);
  }
}

void RemoteCancelListener::serve()
{
  while (!this->Stop.load())
  {
    pollfd wait{ this->Socket, POLLIN, 0 };
    const int ready = ::poll(&wait, 1, kPollTimeout_ms);
    if (ready <= 0 || !(wait.revents & POLLIN))
    {
      continue; // the time-out (to see Stop), or EINTR
    }
    const int connection = ::accept4(this->Socket, nullptr, nullptr, SOCK_CLOEXEC);
    if (connection < 0)
    {
      continue;
    }
    const bool token = this->readToken(connection);
    if (token)
    {
      this->Cancelled = true;
    }
    const char* answer = token ? "cancelling\n" : "wrong token\n";
    (void)!::send(connection, answer, std::strlen(answer), MSG_NOSIGNAL);
    ::close(connection);
  }
}

bool RemoteCancelListener::readToken(int connection) const
{
  timeval timeout{ kReadTimeout_s, 0 };
  ::setsockopt(connection, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof(timeout));
  std::string line;
  char c = 0;
  while (line.size() < kMaximumLine && ::recv(connection, &c, 1, 0) == 1 && c != '\n')
  {
    line.push_back(c);
  }
  if (!line.empty() && line.back() == '\r')
  {
    line.pop_back();
  }
  return line == this->Token;
}

} // namespace vtouch
