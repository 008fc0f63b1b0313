// vtouch::RemoteCancelListener: the first rank's cancel socket (see the header).
#include "vtouchRemoteCancelListener.h"

#include <arpa/inet.h>
#include <netdb.h>
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
    if (token)
    {
      this->forward();
    }
  }
}

void RemoteCancelListener::forwardTo(std::vector<std::pair<std::string, int>> peers)
{
  {
    std::lock_guard<std::mutex> lock(this->PeersMutex);
    this->Peers = std::move(peers);
  }
  if (this->Cancelled.load())
  {
    this->forward();
  }
}

std::string RemoteCancelListener::hostName()
{
  char name[256] = {};
  return ::gethostname(name, sizeof(name) - 1) == 0 ? std::string(name) : std::string("localhost");
}

void RemoteCancelListener::forward()
{
  std::vector<std::pair<std::string, int>> peers;
  {
    std::lock_guard<std::mutex> lock(this->PeersMutex);
    peers.swap(this->Peers); // each peer is told once
  }
  const std::string line = this->Token + "\n";
  for (const auto& [host, port] : peers)
  {
    addrinfo hints{};
    hints.ai_family = AF_INET;
    hints.ai_socktype = SOCK_STREAM;
    addrinfo* found = nullptr;
    if (::getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found) != 0)
    {
      continue; // that rank stops at its next exchange
    }
    const int s = ::socket(AF_INET, SOCK_STREAM | SOCK_CLOEXEC, 0);
    timeval timeout{ kReadTimeout_s, 0 };
    if (s >= 0)
    {
      ::setsockopt(s, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof(timeout)); // bounds connect too
      if (::connect(s, found->ai_addr, found->ai_addrlen) == 0)
      {
        (void)!::send(s, line.data(), line.size(), MSG_NOSIGNAL);
      }
      ::close(s);
    }
    ::freeaddrinfo(found);
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
