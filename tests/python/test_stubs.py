"""The type stubs (python/skyspec.pyi) describe the module as it is: the same public names, the same
members of RenderResult, and for every function and method the same parameters, in order, with the
same keyword-only ones (read from pybind11's signature line). Run by CTest beside test_module.
"""
import ast
import os
import re
import unittest

import skyspec

STUBS = os.path.join(os.environ.get("SKYSPEC_SOURCE_DIR", os.path.join(os.path.dirname(__file__), "..", "..")),
                     "python", "skyspec.pyi")


def stub_tree():
    with open(STUBS) as f:
        return ast.parse(f.read())


def stub_parameters(fn):
    """(positional names, keyword-only names) of a stub function, without self."""
    a = fn.args
    positional = [p.arg for p in a.posonlyargs + a.args if p.arg != "self"]
    return positional, [p.arg for p in a.kwonlyargs]


def module_parameters(obj, name):
    """The same from pybind11's first docstring line, 'name(a: T = x, *, b: U = y) -> R'."""
    first = obj.__doc__.strip().splitlines()[0]
    m = re.match(rf"{name}\((.*)\) ->", first)
    assert m, first
    positional, keyword, star = [], [], False
    depth, part, parts = 0, "", []
    for ch in m.group(1):  # split on the commas outside brackets
        depth += ch in "[(" and 1 or ch in "])" and -1 or 0
        if ch == "," and depth == 0:
            parts.append(part)
            part = ""
        else:
            part += ch
    if part.strip():
        parts.append(part)
    for p in (p.strip() for p in parts):
        if p == "*":
            star = True
            continue
        pname = p.split(":")[0].strip()
        if pname != "self":
            (keyword if star else positional).append(pname)
    return positional, keyword


class StubsMatchTheModule(unittest.TestCase):
    def test_public_names(self):
        tree = stub_tree()
        stubbed = {n.name for n in tree.body if isinstance(n, (ast.FunctionDef, ast.ClassDef))}
        module = {n for n in dir(skyspec) if not n.startswith("_")}
        self.assertEqual(stubbed, module)

    def test_functions_take_the_same_parameters(self):
        for node in stub_tree().body:
            if isinstance(node, ast.FunctionDef):
                with self.subTest(node.name):
                    self.assertEqual(stub_parameters(node), module_parameters(getattr(skyspec, node.name), node.name))

    def test_render_result_members(self):
        cls = next(n for n in stub_tree().body if isinstance(n, ast.ClassDef) and n.name == "RenderResult")
        stubbed = {n.name for n in cls.body if isinstance(n, ast.FunctionDef)}
        module = {n for n in dir(skyspec.RenderResult) if not n.startswith("_")}
        self.assertEqual(stubbed, module)
        for node in (n for n in cls.body if isinstance(n, ast.FunctionDef)):
            member = getattr(skyspec.RenderResult, node.name)
            is_property = isinstance(member, property)
            with self.subTest(node.name):
                self.assertEqual(any(isinstance(d, ast.Name) and d.id == "property" for d in node.decorator_list),
                                 is_property)
                self.assertTrue(ast.get_docstring(node), "no docstring")
                if not is_property:
                    self.assertEqual(stub_parameters(node), module_parameters(member, node.name))


if __name__ == "__main__":
    unittest.main()
