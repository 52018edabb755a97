using System.Runtime.CompilerServices;

// The component tests in tests/dotnet/Drape.Runtime.Tests (run against the Unity stand-in with the
// .NET SDK) call the internal helpers (fixed-step clock, interpolation, pin selection, mesh layout).
[assembly: InternalsVisibleTo("Drape.Runtime.Tests")]
// The editor's pin authoring reads the grid shape the runtime generates.
[assembly: InternalsVisibleTo("Drape.Editor")]
