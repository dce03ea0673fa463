"""What the command-line tests expect of every run, whatever the subcommand
(docs/cli.md#conventions)."""
import json


def assert_usage_error(test, r, needle, args=None):
    """A refused invocation: exit status 2 and exactly one line on stderr, holding `needle`.
    `r`: a finished subprocess.run with text output; `test`: the unittest.TestCase."""
    test.assertEqual(r.returncode, 2, (args, r.stdout, r.stderr))
    test.assertIn(needle, r.stderr)
    test.assertEqual(len(r.stderr.strip().splitlines()), 1, r.stderr)


def quiet_json(test, r):
    """A successful run with --json, piped: exit 0, nothing on stderr (no progress bar); its JSON."""
    test.assertEqual(r.returncode, 0, r.stderr)
    test.assertEqual(r.stderr, "")
    return json.loads(r.stdout)
