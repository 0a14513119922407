"""``--set key.path=value``: changes to a scene's data before it is
validated (array entries by index: ``contact.0.eps_n=10``)."""
import tomllib

from .errors import SceneError, describe, printable


def parse_value(text):
    """A --set value: TOML syntax if it parses (numbers, lists, true), else a string."""
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        return text


def _index(node, key, shown, where):
    """The entry ``key`` of the array ``node``, or SceneError."""
    if not key.isdigit() or int(key) >= len(node):
        valid = f"0..{len(node) - 1}" if node else "it is empty"
        raise SceneError(f"--set {shown}: '{printable(key, 40)}' is not an index of '{where}' ({valid})")
    return int(key)


def apply_override(data, assignment):
    """Apply ``key.path=value`` to the scene data ``data`` (in place)."""
    if "=" not in assignment:
        raise SceneError(f"--set {printable(repr(assignment), 80)}: expected key=value")
    path, text = assignment.split("=", 1)
    keys = path.strip().split(".")
    shown = printable(path.strip(), 80)
    if not all(keys):
        raise SceneError(f"--set {shown}: empty key in the key path")
    node = data
    for i, k in enumerate(keys[:-1]):
        where = ".".join(keys[:i]) or "the scene"
        if isinstance(node, list):
            node = node[_index(node, k, shown, where)]
        elif isinstance(node, dict):
            node = node.setdefault(k, {})
        else:
            raise SceneError(f"--set {shown}: '{where}' is {describe(node)}, not a table")
    last, parent = keys[-1], ".".join(keys[:-1])
    value = parse_value(text.strip())
    if isinstance(node, list):
        i = _index(node, last, shown, parent)
        if isinstance(node[i], dict):
            raise SceneError(f"--set {shown}: cannot assign a whole array entry")
        node[i] = value
    elif isinstance(node, dict):
        node[last] = value
    else:
        raise SceneError(f"--set {shown}: '{parent}' is {describe(node)}, not a table")
