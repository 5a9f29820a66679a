"""The Ray driver on a real cluster. On the head node:   ray start --head --port=6379
On every other node:                                     ray start --address=HEAD_IP:6379
(every node needs `pip install 'pathtrace[ray]'` and the scene file at the same path), then run
this on the head node. A worker node that dies mid-render costs time: Ray re-runs its chunks."""

import pathtrace
from pathtrace import distributed

scene = pathtrace.load_file("/shared/scenes/scene.toml")
film = distributed.render(
    scene,
    spp=4096,
    seed=1,
    width=3840,
    height=2160,
    chunks=64,
    threads=8,  # each chunk is a Ray task asking for 8 CPUs
    address="auto",  # the cluster `ray start` made on this node
    checkpoint="/shared/still.ptfilm",  # a restarted driver renders only what is missing
    progress=lambda done, total: print(f"{done}/{total} spp"),
)
film.write("/shared/still.exr")
