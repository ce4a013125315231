"""The supervisor asks the master about the controller from two threads: its PID learner, every
0.2 s, and a restart. Both once went through one XML-RPC proxy, whose one HTTP connection
cannot carry two requests: a restart that asked while the learner's request was on its way failed
with http.client.CannotSendRequest, and the HA flew 15 s more until it asked again (HiL, a 75 s
wind flight: "the controller did not come back within 60 s").

The fake master below answers lookupNode only once two requests are in it at the same time, so
the two askers' requests always overlap; the shared proxy of old is the negative control."""
import socketserver
import threading
import xmlrpc.server

import rosgraph

from supervisor_core.node_query import ThreadMasters, node_uri

NODE = "/controller_DG808"


class FakeMaster(socketserver.ThreadingMixIn, xmlrpc.server.SimpleXMLRPCServer):
    daemon_threads = True

    def __init__(self):
        super().__init__(("127.0.0.1", 0), logRequests=False, allow_none=True)
        self.both_in = threading.Barrier(2)
        self.register_function(self.lookupNode)
        self.thread = threading.Thread(target=self.serve_forever, daemon=True)
        self.thread.start()

    @property
    def uri(self):
        return "http://127.0.0.1:%d/" % self.server_address[1]

    def lookupNode(self, caller_id, name):  # noqa: N802  (the master API's name)
        try:
            self.both_in.wait(timeout=2.0)
        except threading.BrokenBarrierError:
            pass  # the other request never came: answered all the same
        return [1, "node found", "http://127.0.0.1:45000/" + name.strip("/")]

    def stop(self):
        self.shutdown()
        self.server_close()
        self.thread.join(timeout=5.0)


def ask_at_once(masters_of_thread):
    """node_uri from two threads started together; their answers, in thread order."""
    answers = [None, None]
    go = threading.Barrier(2)

    def ask(i):
        go.wait(timeout=5.0)
        answers[i] = node_uri(masters_of_thread(), NODE)
    threads = [threading.Thread(target=ask, args=(i,)) for i in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=10.0)
    return answers


def test_a_restart_asking_while_the_pid_learner_asks_gets_its_answer():
    master = FakeMaster()
    try:
        masters = ThreadMasters("/hp_supervisor", master_uri=master.uri)
        for _ in range(3):
            master.both_in.reset()
            answers = ask_at_once(masters.get)
            assert answers == ["http://127.0.0.1:45000/controller_DG808"] * 2, answers
    finally:
        master.stop()


def test_one_proxy_shared_by_both_threads_loses_a_request_and_says_none_instead_of_raising():
    master = FakeMaster()
    try:
        shared = rosgraph.Master("/hp_supervisor", master_uri=master.uri)
        answers = ask_at_once(lambda: shared)
        assert None in answers, "the negative control's requests did not collide: %s" % answers
    finally:
        master.stop()
