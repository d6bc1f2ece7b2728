"""The figures of a validation page's runs, kept in a JSON beside the page (OUT_MD's .json).

A page made from runs/<...>/ (channel.py, aspect_ratio.py) can then be regenerated and extended
when some of its runs are no longer on disk: those are read back from the JSON. The JSON is
rewritten each time with every run's record, the runs on disk taking precedence."""
import json
import os


def json_path(out_md):
    """The JSON kept beside the page out_md."""
    return os.path.splitext(out_md)[0] + ".json"


def merge(path, on_disk, to_record):
    """on_disk: {name: run read from disk}; to_record(run) its JSON record. Returns the records
    of path whose names are not on disk, {name: record}, and rewrites path with every run's
    record (nothing is written when there is no run at all)."""
    kept = {}
    if os.path.isfile(path):
        with open(path) as fh:
            kept = json.load(fh)
    extra = {n: r for n, r in kept.items() if n not in on_disk}
    out = dict(extra)
    out.update({n: to_record(r) for n, r in on_disk.items()})
    if out:
        with open(path, "w") as fh:
            json.dump(dict(sorted(out.items())), fh, indent=0, sort_keys=True)
            fh.write("\n")
    return extra
