"""A minimal MQTT 3.1.1 client for the tests (Debian's python has no MQTT module, and the broker's
command-line clients would put a process start between the test and each message): connect with a
username and password, subscribe at QoS 0, publish at QoS 0. A reader thread keeps every message with
the monotonic time it arrived, so a test measures when a tag came and waits on a condition with a
deadline."""
import socket
import struct
import threading
import time


def _string(s):
    b = s.encode()
    return struct.pack("!H", len(b)) + b


def _packet(first_byte, body):
    """A packet: its first byte, the remaining length (MQTT's variable-length integer), the body."""
    length, n = b"", len(body)
    while True:
        digit, n = n % 128, n // 128
        length += bytes([digit | (0x80 if n else 0)])
        if not n:
            return bytes([first_byte]) + length + body


class Message:
    def __init__(self, at, topic, payload):
        self.at = at  # time.monotonic() when it arrived
        self.topic = topic
        self.payload = payload

    def __repr__(self):
        return f"{self.topic} {self.payload!r}"


class MqttClient:
    def __init__(self, port, client_id, username, password, subscribe):
        self._sock = socket.create_connection(("127.0.0.1", port), timeout=10)
        # Clean session; username and password; keep-alive off (the test is shorter than any time-out).
        self._sock.sendall(_packet(0x10, _string("MQTT") + bytes([4, 0xC2]) + struct.pack("!H", 0) +
                                   _string(client_id) + _string(username) + _string(password)))
        kind, body = self._read_packet()
        if kind != 0x20 or body[1] != 0:
            raise RuntimeError(f"the broker refused {username}: CONNACK {body!r}")
        self._sock.sendall(_packet(0x82, struct.pack("!H", 1) + _string(subscribe) + b"\x00"))
        kind, body = self._read_packet()
        if kind != 0x90 or body[2] == 0x80:
            raise RuntimeError(f"the broker refused the subscription to {subscribe}: {body!r}")
        self._sock.settimeout(None)
        self._messages = []
        self._changed = threading.Condition()
        self._closed = False
        threading.Thread(target=self._read_messages, daemon=True).start()

    def publish(self, topic, payload):
        self._sock.sendall(_packet(0x30, _string(topic) + payload.encode()))

    def messages(self):
        with self._changed:
            return list(self._messages)

    def wait_for(self, condition, deadline, what):
        """The first message that `condition` holds for, waiting until the monotonic `deadline`."""
        with self._changed:
            while True:
                for m in self._messages:
                    if condition(m):
                        return m
                left = deadline - time.monotonic()
                if left <= 0 or self._closed:
                    raise TimeoutError(f"no message: {what}")
                self._changed.wait(left)

    def close(self):
        self._sock.sendall(b"\xe0\x00")  # DISCONNECT
        self._sock.close()

    def _read_exactly(self, n):
        data = b""
        while len(data) < n:
            chunk = self._sock.recv(n - len(data))
            if not chunk:
                raise ConnectionError("the broker closed the connection")
            data += chunk
        return data

    def _read_packet(self):
        first = self._read_exactly(1)[0]
        length, shift = 0, 0
        while True:
            digit = self._read_exactly(1)[0]
            length += (digit & 0x7F) << shift
            shift += 7
            if not digit & 0x80:
                break
        return first & 0xF0, self._read_exactly(length)

    def _read_messages(self):
        try:
            while True:
                kind, body = self._read_packet()
                if kind != 0x30:  # a subscription at QoS 0 brings PUBLISH at QoS 0 only (no packet id)
                    continue
                n = struct.unpack("!H", body[:2])[0]
                message = Message(time.monotonic(), body[2:2 + n].decode(), body[2 + n:].decode())
                with self._changed:
                    self._messages.append(message)
                    self._changed.notify_all()
        except (ConnectionError, OSError):
            with self._changed:
                self._closed = True
                self._changed.notify_all()
