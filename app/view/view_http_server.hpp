// The operator view's HTTP transport: httplib parses and routes every request, but no connection
// ever waits in a shared worker pool. One reader thread (epoll) reads each request whole; by its
// kind it then goes to the command thread (no viewer can occupy it), to one of a bounded number of
// stream threads (the excess answered 503 at once), or to the page threads.
#pragma once

#include <httplib.h>

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <deque>
#include <functional>
#include <memory>
#include <mutex>
#include <set>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

namespace rovctl::app {

enum class RequestKind { command, stream, page };

struct ViewHttpLimits {
  int max_streams = 16;  // streams served at once; the next one is answered 503
  int page_threads = 2;  // threads for everything that is neither a command nor a stream
  std::chrono::milliseconds head_timeout{5000};   // a started request must be whole by then
  std::chrono::milliseconds idle_timeout{5000};   // an idle (kept-alive) connection is closed
  std::chrono::milliseconds write_timeout{2000};  // a stream or page client must take its bytes
  std::size_t max_head_bytes = 64 * 1024;         // a longer request head is answered 400
  std::size_t max_body_bytes = 64 * 1024;         // a longer body is answered 413
  std::size_t max_waiting = 1024;  // connections waiting for a request; past it the oldest idle
                                   // one is closed, so idle sockets cannot use up the process's
};

// The request the calling thread is handling (valid inside a route handler only).
struct ViewRequestInfo {
  RequestKind kind = RequestKind::page;
  // When the reader saw the request's first byte (its connection's accept, at the earliest).
  std::chrono::steady_clock::time_point received_at;
  int socket = -1;
  // The client closed or reset its connection (it gave up waiting for the answer).
  bool client_gone() const;
};

class ViewHttpServer : public httplib::Server {
 public:
  using Classifier = std::function<RequestKind(std::string_view method, std::string_view path)>;
  ViewHttpServer(ViewHttpLimits limits, Classifier classify);
  ~ViewHttpServer() override;
  ViewHttpServer(const ViewHttpServer&) = delete;
  ViewHttpServer& operator=(const ViewHttpServer&) = delete;

  // Starts the reader and the worker threads (`lower` runs first on every stream and page thread
  // to put it below the tick). Call after binding, before listen_after_bind().
  bool start_dispatch(const std::function<void()>& lower, std::string& error);
  // After httplib's stop(): closes every connection and joins every thread. Idempotent.
  void stop_dispatch();

  int streams_open() const { return streams_open_.load(); }
  std::uint64_t streams_refused() const { return streams_refused_.load(); }
  static const ViewRequestInfo* current();

  struct Connection;  // a socket and the bytes read from it (defined in the .cpp)

 private:
  // httplib's accept loop calls this for each accepted socket; it only hands it to the reader.
  bool process_and_close_socket(socket_t sock) override;

  struct Queue {
    std::mutex mutex;
    std::condition_variable ready;
    std::deque<std::unique_ptr<Connection>> items;
    bool closed = false;
  };
  void read_loop();
  void work_loop(Queue& queue, RequestKind kind);
  void adopt(std::unique_ptr<Connection> c);  // to the reader (new or kept alive)
  void serve(std::unique_ptr<Connection> c, RequestKind kind);
  void track(int fd, bool on);

  ViewHttpLimits limits_;
  Classifier classify_;
  int epoll_fd_ = -1;
  int wake_fd_ = -1;
  std::atomic<bool> stopping_{false};
  bool dispatching_ = false;

  std::mutex inbox_mutex_;
  std::vector<std::unique_ptr<Connection>> inbox_;

  Queue commands_;
  Queue streams_;
  Queue pages_;
  std::vector<std::thread> threads_;

  std::mutex busy_mutex_;
  std::set<int> busy_;  // sockets a worker is serving (shut down on stop to end their writes)

  std::atomic<int> streams_open_{0};
  std::atomic<std::uint64_t> streams_refused_{0};
};

}  // namespace rovctl::app
