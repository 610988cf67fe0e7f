// The reader (epoll, non-blocking, whole requests only), the three kinds of worker, and the
// buffered stream through which httplib parses a request the reader has already read.
#include "app/view/view_http_server.hpp"

#include <arpa/inet.h>
#include <netinet/in.h>
#include <poll.h>
#include <sys/epoll.h>
#include <sys/eventfd.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <unordered_map>

namespace rovctl::app {

using Clock = std::chrono::steady_clock;

struct ViewHttpServer::Connection {
  int fd = -1;
  std::string buf;                // read, not yet parsed by httplib
  Clock::time_point received_at;  // first byte of the request in `buf`
  Clock::time_point idle_since;   // accepted, or its last answer sent
  bool draining = false;          // answered and closing: input is read and dropped
  Clock::time_point drain_until;
  explicit Connection(int s) : fd(s), idle_since(Clock::now()) {}
  ~Connection() {
    if (fd >= 0) ::close(fd);
  }
  Connection(const Connection&) = delete;
  Connection& operator=(const Connection&) = delete;
};

namespace {

thread_local const ViewRequestInfo* t_current = nullptr;

// httplib's accept loop hands each socket to a task queue: this one runs the hand-off at once,
// on the accept thread (it only queues the socket for the reader).
class InlineQueue final : public httplib::TaskQueue {
 public:
  void enqueue(std::function<void()> fn) override { fn(); }
  void shutdown() override {}
};

int poll_ms(std::chrono::milliseconds d) { return static_cast<int>(d.count()); }

void address_of(const sockaddr_storage& a, std::string& ip, int& port) {
  char text[INET6_ADDRSTRLEN] = {};
  if (a.ss_family == AF_INET) {
    const auto& v4 = reinterpret_cast<const sockaddr_in&>(a);
    inet_ntop(AF_INET, &v4.sin_addr, text, sizeof(text));
    port = ntohs(v4.sin_port);
  } else if (a.ss_family == AF_INET6) {
    const auto& v6 = reinterpret_cast<const sockaddr_in6&>(a);
    inet_ntop(AF_INET6, &v6.sin6_addr, text, sizeof(text));
    port = ntohs(v6.sin6_port);
  }
  ip = text;
}

// A request the reader has read whole: httplib parses it from memory and never waits for a
// client's bytes. Writes wait at most `write_timeout` for the client (0: never wait).
class BufferedStream final : public httplib::Stream {
 public:
  BufferedStream(const std::string& buf, int fd, std::chrono::milliseconds write_timeout)
      : buf_(buf), fd_(fd), write_timeout_(write_timeout) {}
  std::size_t consumed() const { return pos_; }

  bool is_readable() const override { return pos_ < buf_.size(); }
  bool is_writable() const override {
    pollfd p{fd_, POLLOUT, 0};
    return ::poll(&p, 1, poll_ms(write_timeout_)) > 0 && (p.revents & (POLLERR | POLLHUP)) == 0;
  }
  ssize_t read(char* ptr, std::size_t size) override {
    const std::size_t n = std::min(size, buf_.size() - pos_);
    std::memcpy(ptr, buf_.data() + pos_, n);
    pos_ += n;
    return static_cast<ssize_t>(n);
  }
  // All or nothing: httplib sends a response's head in one write and ignores a short one.
  ssize_t write(const char* ptr, std::size_t size) override {
    std::size_t sent = 0;
    while (sent < size) {
      const ssize_t n = ::send(fd_, ptr + sent, size - sent, MSG_DONTWAIT | MSG_NOSIGNAL);
      if (n > 0) {
        sent += static_cast<std::size_t>(n);
      } else if (n < 0 && (errno == EAGAIN || errno == EWOULDBLOCK) && write_timeout_.count() > 0 &&
                 is_writable()) {
        continue;
      } else if (n < 0 && errno == EINTR) {
        continue;
      } else {
        return -1;
      }
    }
    return static_cast<ssize_t>(size);
  }
  void get_remote_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage a{};
    socklen_t n = sizeof(a);
    if (getpeername(fd_, reinterpret_cast<sockaddr*>(&a), &n) == 0) address_of(a, ip, port);
  }
  void get_local_ip_and_port(std::string& ip, int& port) const override {
    sockaddr_storage a{};
    socklen_t n = sizeof(a);
    if (getsockname(fd_, reinterpret_cast<sockaddr*>(&a), &n) == 0) address_of(a, ip, port);
  }
  socket_t socket() const override { return fd_; }

 private:
  const std::string& buf_;
  int fd_;
  std::chrono::milliseconds write_timeout_;
  std::size_t pos_ = 0;
};

// Case-insensitive header name match.
bool same_name(std::string_view a, std::string_view b) {
  return a.size() == b.size() && std::equal(a.begin(), a.end(), b.begin(), [](char x, char y) {
           return std::tolower(static_cast<unsigned char>(x)) ==
                  std::tolower(static_cast<unsigned char>(y));
         });
}

std::string_view trim(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
    s.remove_suffix(1);
  return s;
}

struct Head {
  std::string_view method;
  std::string path;  // decoded, without the query
  std::size_t body_bytes = 0;
  bool chunked = false;
  bool bad_length = false;
};

Head parse_head(std::string_view head) {
  Head h;
  const std::size_t eol = head.find('\n');
  const std::string_view line = trim(head.substr(0, eol));
  const std::size_t sp = line.find(' ');
  h.method = line.substr(0, sp);
  if (sp != std::string_view::npos) {
    std::string_view target = line.substr(sp + 1);
    target = target.substr(0, target.find(' '));
    target = target.substr(0, target.find('?'));
    // As httplib routes: on the decoded path, so "/%65vents" is a stream too.
    h.path = httplib::detail::decode_url(std::string(target), false);
  }
  for (std::size_t at = eol; at != std::string_view::npos && at + 1 < head.size();) {
    const std::size_t next = head.find('\n', at + 1);
    const std::string_view field = head.substr(at + 1, next - at - 1);
    at = next;
    const std::size_t colon = field.find(':');
    if (colon == std::string_view::npos) continue;
    const std::string_view name = trim(field.substr(0, colon));
    const std::string_view value = trim(field.substr(colon + 1));
    if (same_name(name, "Transfer-Encoding")) h.chunked = true;
    if (same_name(name, "Content-Length")) {
      std::size_t n = 0;
      for (char c : value) {
        if (c < '0' || c > '9' || n > (std::size_t{1} << 40)) {
          h.bad_length = true;
          break;
        }
        n = n * 10 + static_cast<std::size_t>(c - '0');
      }
      h.bad_length = h.bad_length || value.empty();
      h.body_bytes = n;
    }
  }
  return h;
}

}  // namespace

bool ViewRequestInfo::client_gone() const {
  pollfd p{socket, POLLIN | POLLRDHUP, 0};
  if (::poll(&p, 1, 0) <= 0) return false;
  return (p.revents & (POLLERR | POLLHUP | POLLRDHUP | POLLNVAL)) != 0;
}

ViewHttpServer::ViewHttpServer(ViewHttpLimits limits, Classifier classify)
    : limits_(limits), classify_(std::move(classify)) {
  new_task_queue = [] { return new InlineQueue(); };
}

ViewHttpServer::~ViewHttpServer() {
  stop();
  stop_dispatch();
}

const ViewRequestInfo* ViewHttpServer::current() { return t_current; }

bool ViewHttpServer::start_dispatch(const std::function<void()>& lower, std::string& error) {
  if (dispatching_) return true;
  epoll_fd_ = epoll_create1(EPOLL_CLOEXEC);
  wake_fd_ = eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC);
  if (epoll_fd_ < 0 || wake_fd_ < 0) {
    error = std::string("operator view: epoll/eventfd: ") + std::strerror(errno);
    return false;
  }
  epoll_event ev{};
  ev.events = EPOLLIN;
  ev.data.fd = wake_fd_;
  epoll_ctl(epoll_fd_, EPOLL_CTL_ADD, wake_fd_, &ev);
  // httplib listens with a backlog of 5: a burst of viewers would overflow it and a command's
  // connection would wait for a SYN retry (1 s). The accept loop drains quickly; widen the queue.
  if (svr_sock_ != INVALID_SOCKET) ::listen(svr_sock_, SOMAXCONN);
  stopping_ = false;
  dispatching_ = true;
  // The reader and the command thread keep the process's normal priority; every other view
  // thread runs `lower` first.
  threads_.emplace_back([this] { read_loop(); });
  threads_.emplace_back([this] { work_loop(commands_, RequestKind::command); });
  for (int i = 0; i < limits_.max_streams; ++i) {
    threads_.emplace_back([this, lower] {
      lower();
      work_loop(streams_, RequestKind::stream);
    });
  }
  for (int i = 0; i < limits_.page_threads; ++i) {
    threads_.emplace_back([this, lower] {
      lower();
      work_loop(pages_, RequestKind::page);
    });
  }
  return true;
}

void ViewHttpServer::stop_dispatch() {
  if (!dispatching_) return;
  stopping_ = true;
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t w = ::write(wake_fd_, &one, sizeof(one));
  for (Queue* q : {&commands_, &streams_, &pages_}) {
    std::lock_guard<std::mutex> lock(q->mutex);
    q->closed = true;
    q->ready.notify_all();
  }
  {
    // A worker blocked writing to a slow client returns at once.
    std::lock_guard<std::mutex> lock(busy_mutex_);
    for (int fd : busy_) ::shutdown(fd, SHUT_RDWR);
  }
  for (std::thread& t : threads_) t.join();
  threads_.clear();
  for (Queue* q : {&commands_, &streams_, &pages_}) {
    std::lock_guard<std::mutex> lock(q->mutex);
    q->items.clear();
    q->closed = false;
  }
  {
    std::lock_guard<std::mutex> lock(inbox_mutex_);
    inbox_.clear();
  }
  streams_open_ = 0;  // admitted streams still queued were closed above
  ::close(epoll_fd_);
  ::close(wake_fd_);
  epoll_fd_ = wake_fd_ = -1;
  dispatching_ = false;
}

bool ViewHttpServer::process_and_close_socket(socket_t sock) {
  adopt(std::make_unique<Connection>(sock));
  return true;
}

void ViewHttpServer::adopt(std::unique_ptr<Connection> c) {
  if (stopping_) return;  // closed by its destructor
  {
    std::lock_guard<std::mutex> lock(inbox_mutex_);
    inbox_.push_back(std::move(c));
  }
  const std::uint64_t one = 1;
  [[maybe_unused]] const ssize_t w = ::write(wake_fd_, &one, sizeof(one));
}

void ViewHttpServer::track(int fd, bool on) {
  std::lock_guard<std::mutex> lock(busy_mutex_);
  if (on) {
    busy_.insert(fd);
  } else {
    busy_.erase(fd);
  }
}

void ViewHttpServer::read_loop() {
  std::unordered_map<int, std::unique_ptr<Connection>> waiting;
  std::vector<int> ready;
  std::vector<std::unique_ptr<Connection>> arrived;
  epoll_event events[64];
  auto next_sweep = Clock::now();

  const auto close_conn = [&](int fd) { waiting.erase(fd); };  // closing removes it from epoll
  // An answer the reader gives itself (refusals): sent without waiting, then the input is read
  // and dropped until the client closes, so that it receives the answer rather than a reset.
  const auto refuse = [&](Connection& c, int status, const char* reason, const std::string& body) {
    const std::string msg =
        "HTTP/1.1 " + std::to_string(status) + " " + reason +
        "\r\nContent-Type: text/plain\r\nContent-Length: " + std::to_string(body.size()) +
        "\r\nConnection: close\r\n\r\n" + body;
    [[maybe_unused]] const ssize_t n =
        ::send(c.fd, msg.data(), msg.size(), MSG_DONTWAIT | MSG_NOSIGNAL);
    ::shutdown(c.fd, SHUT_WR);
    c.buf.clear();
    c.draining = true;
    c.drain_until = Clock::now() + std::chrono::seconds(1);
  };

  const auto handle = [&](int fd) {
    auto it = waiting.find(fd);
    if (it == waiting.end()) return;
    Connection& c = *it->second;
    const std::size_t cap = limits_.max_head_bytes + limits_.max_body_bytes + 1;
    bool eof = false;
    char chunk[16384];
    for (;;) {
      const ssize_t n = ::recv(fd, chunk, sizeof(chunk), MSG_DONTWAIT);
      if (n > 0) {
        if (c.draining) continue;
        if (c.buf.empty()) c.received_at = Clock::now();
        c.buf.append(chunk, static_cast<std::size_t>(n));
        if (c.buf.size() >= cap) break;
      } else if (n == 0) {
        eof = true;
        break;
      } else if (errno == EINTR) {
        continue;
      } else if (errno == EAGAIN || errno == EWOULDBLOCK) {
        break;
      } else {
        close_conn(fd);
        return;
      }
    }
    if (c.draining) {
      if (eof) close_conn(fd);
      return;
    }
    if (c.buf.empty()) {
      if (eof) close_conn(fd);
      return;
    }
    const std::size_t head_end = c.buf.find("\r\n\r\n");
    if (head_end == std::string::npos) {
      if (c.buf.size() > limits_.max_head_bytes) {
        refuse(c, 400, "Bad Request", "request head too large\n");
      } else if (eof) {
        close_conn(fd);
      }
      return;
    }
    const Head h = parse_head(std::string_view(c.buf).substr(0, head_end + 2));
    if (h.chunked || h.bad_length) {
      refuse(c, 400, "Bad Request", "a request body needs a plain Content-Length\n");
      return;
    }
    if (h.body_bytes > limits_.max_body_bytes) {
      refuse(c, 413, "Payload Too Large", "request body too large\n");
      return;
    }
    if (c.buf.size() < head_end + 4 + h.body_bytes) {
      if (eof) close_conn(fd);
      return;  // the rest of the body is still coming
    }
    const RequestKind kind = classify_(h.method, h.path);
    Queue* queue = &pages_;
    if (kind == RequestKind::command) {
      queue = &commands_;
    } else if (kind == RequestKind::stream) {
      if (streams_open_.load() >= limits_.max_streams) {
        ++streams_refused_;
        refuse(c, 503, "Service Unavailable",
               "too many viewers: " + std::to_string(limits_.max_streams) +
                   " streams open (operator_view.max_streams); ABORT and START still work\n");
        return;
      }
      ++streams_open_;
      queue = &streams_;
    } else {
      std::lock_guard<std::mutex> lock(pages_.mutex);
      if (pages_.items.size() >= limits_.max_waiting) {
        refuse(c, 503, "Service Unavailable", "busy\n");
        return;
      }
    }
    epoll_ctl(epoll_fd_, EPOLL_CTL_DEL, fd, nullptr);
    std::unique_ptr<Connection> owned = std::move(it->second);
    waiting.erase(it);
    {
      std::lock_guard<std::mutex> lock(queue->mutex);
      queue->items.push_back(std::move(owned));
    }
    queue->ready.notify_one();
  };

  while (!stopping_) {
    const int n = epoll_wait(epoll_fd_, events, 64, ready.empty() ? 100 : 0);
    for (int i = 0; i < n; ++i) {
      if (events[i].data.fd == wake_fd_) {
        std::uint64_t count = 0;
        [[maybe_unused]] const ssize_t r = ::read(wake_fd_, &count, sizeof(count));
      } else {
        ready.push_back(events[i].data.fd);
      }
    }
    {
      std::lock_guard<std::mutex> lock(inbox_mutex_);
      arrived.swap(inbox_);
    }
    for (auto& c : arrived) {
      const int fd = c->fd;
      epoll_event ev{};
      ev.events = EPOLLIN | EPOLLRDHUP;
      ev.data.fd = fd;
      if (epoll_ctl(epoll_fd_, EPOLL_CTL_ADD, fd, &ev) != 0) continue;  // closed by ~Connection
      // A kept-alive connection may hold the next request already (pipelined).
      if (!c->buf.empty()) ready.push_back(fd);
      waiting[fd] = std::move(c);
    }
    arrived.clear();
    // Too many waiting: the longest idle one goes, so idle sockets cannot use up descriptors.
    while (waiting.size() > limits_.max_waiting) {
      auto oldest = waiting.end();
      for (auto it = waiting.begin(); it != waiting.end(); ++it) {
        if (oldest == waiting.end() || it->second->idle_since < oldest->second->idle_since)
          oldest = it;
      }
      waiting.erase(oldest);
    }
    std::vector<int> now_ready;
    now_ready.swap(ready);
    for (int fd : now_ready) handle(fd);

    const auto now = Clock::now();
    if (now < next_sweep) continue;
    next_sweep = now + std::chrono::milliseconds(100);
    for (auto it = waiting.begin(); it != waiting.end();) {
      const Connection& c = *it->second;
      const bool expired = c.draining      ? now > c.drain_until
                           : c.buf.empty() ? now - c.idle_since > limits_.idle_timeout
                                           : now - c.received_at > limits_.head_timeout;
      it = expired ? waiting.erase(it) : std::next(it);
    }
  }
}

void ViewHttpServer::work_loop(Queue& queue, RequestKind kind) {
  for (;;) {
    std::unique_ptr<Connection> c;
    {
      std::unique_lock<std::mutex> lock(queue.mutex);
      queue.ready.wait(lock, [&] { return queue.closed || !queue.items.empty(); });
      if (queue.closed) break;
      c = std::move(queue.items.front());
      queue.items.pop_front();
    }
    serve(std::move(c), kind);
  }
}

void ViewHttpServer::serve(std::unique_ptr<Connection> c, RequestKind kind) {
  track(c->fd, true);
  const ViewRequestInfo info{kind, c->received_at, c->fd};
  t_current = &info;
  // A command's answer is small and goes out without waiting: a client that does not read
  // cannot hold the command thread.
  BufferedStream stream(
      c->buf, c->fd,
      kind == RequestKind::command ? std::chrono::milliseconds(0) : limits_.write_timeout);
  const bool close = kind == RequestKind::stream;
  bool closed = close;
  const bool ok = process_request(stream, close, closed, nullptr);
  t_current = nullptr;
  track(c->fd, false);
  if (kind == RequestKind::stream) --streams_open_;
  c->buf.erase(0, stream.consumed());
  if (ok && !closed && !stopping_) {
    c->idle_since = Clock::now();
    adopt(std::move(c));
  }
}

}  // namespace rovctl::app
