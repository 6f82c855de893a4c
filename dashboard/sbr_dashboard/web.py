# SPDX-License-Identifier: MIT
"""The live page: Python's standard-library HTTP server, the state pushed to the browser
as server-sent events (GET /events, one JSON snapshot per change, at most 10 per second,
a comment line every second to keep the connection alive).

Routes: /  (the page), /static/<file>, /events (SSE), /state.json (one snapshot),
/dbc.json (the DBC's class names, for the page's legend)."""
import json
import os
import threading
from http.server import BaseHTTPRequestHandler, ThreadingHTTPServer

STATIC = os.path.join(os.path.dirname(os.path.abspath(__file__)), "static")
TYPES = {".html": "text/html; charset=utf-8", ".js": "text/javascript; charset=utf-8",
         ".css": "text/css; charset=utf-8", ".svg": "image/svg+xml"}


def make_handler(monitor):
    class Handler(BaseHTTPRequestHandler):
        server_version = "sbr-dashboard"

        def log_message(self, fmt, *args):  # quiet
            pass

        def _send(self, code, body, ctype):
            self.send_response(code)
            self.send_header("Content-Type", ctype)
            self.send_header("Content-Length", str(len(body)))
            self.send_header("Cache-Control", "no-store")
            self.end_headers()
            self.wfile.write(body)

        def do_GET(self):
            path = self.path.split("?", 1)[0]
            if path == "/":
                path = "/static/index.html"
            if path == "/state.json":
                self._send(200, json.dumps(monitor.snapshot()).encode(), "application/json")
            elif path == "/events":
                self._events()
            elif path.startswith("/static/"):
                name = os.path.basename(path)
                full = os.path.join(STATIC, name)
                ext = os.path.splitext(name)[1]
                if ext in TYPES and os.path.isfile(full):
                    with open(full, "rb") as f:
                        self._send(200, f.read(), TYPES[ext])
                else:
                    self._send(404, b"not found", "text/plain")
            else:
                self._send(404, b"not found", "text/plain")

        def _events(self):
            self.send_response(200)
            self.send_header("Content-Type", "text/event-stream")
            self.send_header("Cache-Control", "no-store")
            self.send_header("Connection", "keep-alive")
            self.end_headers()
            self.server.client_connected.set()
            version = -1
            try:
                while not self.server.stopping.is_set():
                    new = monitor.wait_change(version, 1.0)
                    if new == version:
                        self.wfile.write(b": keep-alive\n\n")
                    else:
                        version = new
                        data = json.dumps(monitor.snapshot(), separators=(",", ":"))
                        self.wfile.write(f"id: {version}\ndata: {data}\n\n".encode())
                    self.wfile.flush()
                    if self.server.stopping.wait(0.1):
                        break
            except (BrokenPipeError, ConnectionResetError):
                pass

    return Handler


class WebServer:
    def __init__(self, monitor, host="127.0.0.1", port=8080):
        self.httpd = ThreadingHTTPServer((host, port), make_handler(monitor))
        self.httpd.daemon_threads = True
        self.httpd.stopping = threading.Event()
        self.httpd.client_connected = threading.Event()  # a page opened /events
        self.thread = None

    @property
    def url(self):
        host, port = self.httpd.server_address[:2]
        return f"http://{host}:{port}/"

    def start(self):
        self.thread = threading.Thread(target=self.httpd.serve_forever, daemon=True)
        self.thread.start()

    def stop(self):
        self.httpd.stopping.set()
        self.httpd.shutdown()
        self.httpd.server_close()
