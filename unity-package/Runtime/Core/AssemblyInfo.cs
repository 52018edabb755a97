using System.Runtime.CompilerServices;

// The Core tests (Unity Test Runner and tests/dotnet) call the raw bindings directly.
[assembly: InternalsVisibleTo("Drape.Core.Tests")]
